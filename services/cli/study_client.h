// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_STUDY_CLIENT_H_
#define DCS_SERVICES_CLI_STUDY_CLIENT_H_

// Where `dcs study` keeps a study: in a local SQLite file (the coordinator's store, opened in
// this process), or on the coordinator at an address, over gRPC. The same calls either way;
// creating and asking carry request ids, so a call retried after a lost answer does not make a
// second study or trial. Not thread-safe.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "coordinator/study_table.h"

namespace dcs::services::cli {

class StudyClient {
 public:
  virtual ~StudyClient() = default;
  virtual absl::StatusOr<coordinator::StudyRecord> Create(
      const coordinator::StudySubmission& submission) = 0;
  virtual absl::StatusOr<coordinator::StudyRecord> Get(const std::string& study_id) = 0;
  // Every study, oldest first.
  virtual absl::StatusOr<std::vector<coordinator::StudyRecord>> List() = 0;
  // The study's trials, by number.
  virtual absl::StatusOr<std::vector<coordinator::StudyTrial>> Trials(
      const std::string& study_id) = 0;
  virtual absl::StatusOr<coordinator::StudyTrial> Ask(const std::string& study_id,
                                                      const std::string& request_id) = 0;
  virtual absl::StatusOr<coordinator::StudyTrial> Tell(const std::string& study_id, int64_t number,
                                                       coordinator::TrialState state,
                                                       double value) = 0;
  // Whether the study's pruner stops the trial after its value at `step`.
  virtual absl::StatusOr<bool> Report(const std::string& study_id, int64_t number, int64_t step,
                                      double value) = 0;
};

// What opening a study store file that does not exist does: only `dcs studies create` makes one;
// every other command refuses it, so that a mistyped path creates no file.
enum class MissingStore { kCreate, kRefuse };

// The study store in the SQLite file `path`. If it does not exist: created (kCreate), or
// NOT_FOUND naming it (kRefuse).
absl::StatusOr<std::unique_ptr<StudyClient>> OpenLocalStudies(const std::string& path,
                                                              MissingStore missing);

// The coordinator at `address`; each call has `timeout`, and transient failures are retried.
std::unique_ptr<StudyClient> ConnectStudies(const std::string& address, absl::Duration timeout);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_STUDY_CLIENT_H_
