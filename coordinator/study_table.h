// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STUDY_TABLE_H_
#define DCS_COORDINATOR_STUDY_TABLE_H_

// The store's studies (coordinator/store.h holds the whole store): ask-and-tell, as Optuna's.
// A study is a search space, an objective's direction and a sampler; its trials are asked for,
// reported on and told their end. Asking samples inside the transaction that stores the trial,
// so trials asked at once from several clients see each other (the constant liar needs it).
//
// Thread-safe: every call is one transaction on the store's one connection; it returns after
// the transaction committed. Times are passed in (tests drive the clock).

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "common/enum_names.h"
#include "coordinator/pruners.h"
#include "coordinator/sampler.h"
#include "coordinator/tpe_sampler.h"

namespace dcs::coordinator {

namespace internal {
class StoreConnection;
}  // namespace internal

// The samplers a study may use (coordinator/sampler.h).
enum class SamplerKind { kTpe, kRandom };
inline constexpr EnumName<SamplerKind> kSamplerKindNames[] = {{SamplerKind::kTpe, "tpe"},
                                                              {SamplerKind::kRandom, "random"}};
static_assert(InEnumOrder(kSamplerKindNames));

// A study as created: a search space, an objective's direction and a sampler
// (Optuna 4.9's).
struct StudySubmission {
  std::string request_id;  // client-chosen; a repeated id returns the study it created
  std::string name;
  std::string space;  // the search space's YAML (run/search_space_yaml.h)
  SamplerKind sampler = SamplerKind::kTpe;
  uint64_t seed = 0;
  Direction direction = Direction::kMinimize;
  TpeOptions tpe;  // for SamplerKind::kTpe (its ParzenOptions beyond `multivariate` are fixed)
  PrunerOptions pruner;
};

struct StudyRecord {
  std::string id;  // "study-<n>"
  StudySubmission submission;
  std::string sweep_id;  // the study sweep that asks and tells it; empty for ask-and-tell
  std::vector<std::pair<TrialState, int64_t>> trials_by_state;  // every state, zeros included
  std::optional<StudyTrial> best;  // the best complete trial (the first of equals)
  absl::Time created_at;
};

class StudyTable {
 public:
  StudyTable(const StudyTable&) = delete;
  StudyTable& operator=(const StudyTable&) = delete;

  // Creates a study, or returns the one `submission.request_id` already created.
  // INVALID_ARGUMENT for an empty request id, a space that does not parse or validate (naming
  // the problem), or TPE or pruner options out of range.
  absl::StatusOr<StudyRecord> CreateStudy(const StudySubmission& submission, absl::Time now);
  // NOT_FOUND for an unknown id.
  absl::StatusOr<StudyRecord> GetStudy(absl::string_view study_id);
  // Every study, oldest first.
  absl::StatusOr<std::vector<StudyRecord>> ListStudies();
  // A new running trial, numbered after the study's others, with the values its sampler gives
  // given every trial so far; or the trial `request_id` already asked for (a retry).
  // NOT_FOUND for an unknown study; INVALID_ARGUMENT for an empty request id.
  absl::StatusOr<StudyTrial> AskTrial(absl::string_view study_id, absl::string_view request_id,
                                      absl::Time now);
  // Finishes a running trial: complete with `value` (a NaN value fails it, as Optuna's tell
  // does; ±inf is a value), pruned (its value, if any, is its last report), or failed.
  // Telling a finished trial what it was told (a retry) returns it unchanged. NOT_FOUND for an
  // unknown study or trial; FAILED_PRECONDITION if the trial finished otherwise (naming its
  // state); INVALID_ARGUMENT for `state` running.
  absl::StatusOr<StudyTrial> TellTrial(absl::string_view study_id, int64_t number,
                                       TrialState state, double value, absl::Time now);
  // Records a running trial's intermediate value at `step` (a repeated step keeps the first,
  // as Optuna's report) and returns whether the study's pruner says to stop it (never with no
  // pruner; the caller then tells it pruned). NOT_FOUND; FAILED_PRECONDITION if the trial has
  // finished.
  absl::StatusOr<bool> ReportTrial(absl::string_view study_id, int64_t number, int64_t step,
                                   double value);
  // The study's trials, by number. NOT_FOUND for an unknown study.
  absl::StatusOr<std::vector<StudyTrial>> ListStudyTrials(absl::string_view study_id);

 private:
  friend class Store;
  explicit StudyTable(internal::StoreConnection& connection) : connection_(connection) {}

  internal::StoreConnection& connection_;  // the Store's, which owns this table too
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_STUDY_TABLE_H_
