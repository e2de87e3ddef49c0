// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_RUN_CLIENT_H_
#define DCS_SERVICES_CLI_RUN_CLIENT_H_

// The coordinator's runs and sweeps, as the `dcs` client uses them: submit, follow, list,
// cancel, download; a sweep's results; a backup of the coordinator's store. Every call but a
// watch has a deadline (`timeout`); errors are annotated with the coordinator's address.
// Thread-safe.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.pb.h"
#include "dcs/v1/run.pb.h"
#include "dcs/v1/sweep.pb.h"
#include "services/cli/training_report.h"
#include "services/cli/watch_call.h"

namespace dcs::services::cli {

// A new random request id (32 hex digits), which makes a submission's retry idempotent.
std::string NewRequestId();

// Queues the run of `config` (named `config_name` in errors), with `seed` if given, under a
// new random request id (resent as is if the call must be retried). INVALID_ARGUMENT from the
// coordinator names the field, its path and line.
absl::StatusOr<v1::Run> SubmitRun(const std::string& address, const std::string& config,
                                  const std::string& config_name, std::optional<uint64_t> seed,
                                  absl::Duration timeout);

absl::StatusOr<v1::Run> GetRun(const std::string& address, const std::string& run_id,
                               absl::Duration timeout);
absl::StatusOr<std::vector<v1::Run>> ListRuns(const std::string& address,
                                              absl::Duration timeout);
absl::StatusOr<v1::Run> CancelRun(const std::string& address, const std::string& run_id,
                                  absl::Duration timeout);
// Removes ended runs for good, all of them or none (DeleteRuns), and returns them as they were.
// Not retried: a removal whose answer was lost would then be NOT_FOUND.
absl::StatusOr<std::vector<v1::Run>> DeleteRuns(const std::string& address,
                                                const std::vector<std::string>& run_ids,
                                                absl::Duration timeout);

// Follows run `run_id` until it ends, on one stream from the coordinator, which sends only
// changes (services/cli/watch_call.h): `on_update` gets the run whenever its progress or state
// changed. Returns the ended run; CANCELLED once interrupted; other errors (NOT_FOUND for an
// unknown run) as the coordinator gave them.
absl::StatusOr<v1::Run> WatchRun(const std::string& address, const std::string& run_id,
                                 const WatchCallbacks<v1::Run>& callbacks);

// Follows sweep `sweep_id` (with its runs) until it ends, as WatchRun follows a run: returns
// the ended sweep.
absl::StatusOr<v1::GetSweepResponse> WatchSweep(
    const std::string& address, const std::string& sweep_id,
    const WatchCallbacks<v1::GetSweepResponse>& callbacks);

// What `dcs` says on stderr when a watch lost the coordinator (WatchCallbacks::on_lost).
std::string WatchLostMessage(const absl::Status& status);

// Writes run `run_id`'s files (config, checkpoints, evaluation log) into `dir`, as `dcs train
// --out dir` lays them out. INVALID_ARGUMENT for a file path that would leave `dir`.
absl::Status DownloadRun(const std::string& address, const std::string& run_id,
                         const std::string& dir, absl::Duration timeout);

// Writes a backup of the coordinator's store to `out`, atomically, once every piece is in and
// the whole has the size and SHA-256 the coordinator gave (DATA_LOSS otherwise), and returns
// the first piece without its data: the size, the digest and what the backup holds.
absl::StatusOr<v1::BackupPiece> BackupStore(const std::string& address, const std::string& out,
                                            absl::Duration timeout);

// Queues the sweep of `spec` (named `spec_name` in errors; `name` when the spec gives none)
// under a new random request id, resent as is if the call must be retried. INVALID_ARGUMENT
// from the coordinator lists every problem of the spec with its path and line.
absl::StatusOr<v1::Sweep> SubmitSweep(const std::string& address, const std::string& spec,
                                      const std::string& spec_name, const std::string& name,
                                      absl::Duration timeout);
// The sweep and its runs.
absl::StatusOr<v1::GetSweepResponse> GetSweep(const std::string& address,
                                              const std::string& sweep_id,
                                              absl::Duration timeout);
absl::StatusOr<std::vector<v1::Sweep>> ListSweeps(const std::string& address,
                                                  absl::Duration timeout);
absl::StatusOr<v1::Sweep> CancelSweep(const std::string& address, const std::string& sweep_id,
                                      absl::Duration timeout);
// Removes ended sweeps with their runs for good, as DeleteRuns removes runs.
absl::StatusOr<v1::DeleteSweepsResponse> DeleteSweeps(const std::string& address,
                                                      const std::vector<std::string>& sweep_ids,
                                                      absl::Duration timeout);
absl::StatusOr<v1::RetrySweepResponse> RetrySweep(const std::string& address,
                                                  const std::string& sweep_id,
                                                  absl::Duration timeout);
// `scores_only`: as GetSweepResultsRequest.scores_only.
absl::StatusOr<v1::SweepResults> GetSweepResults(const std::string& address,
                                                 const std::string& sweep_id, bool scores_only,
                                                 absl::Duration timeout);

// The progress line of a run (training_report.h).
ProgressLine ProgressLineOf(const v1::RunProgress& progress);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_RUN_CLIENT_H_
