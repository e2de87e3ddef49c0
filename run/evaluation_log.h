// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_EVALUATION_LOG_H_
#define DCS_RUN_EVALUATION_LOG_H_

// A run's evaluation log: its evaluations in order with the paper's two per-run scores, last and
// best-anytime (docs/reference.md, "Scores"), written to the run's output directory as
//   evaluations.csv   one row per evaluation and context:
//                     step,updates,split,value,episodes,mean,std,seconds
//   evaluations.json  a dcs.v1.EvaluationLog (proto/dcs/v1/evaluation.proto) as JSON
//                     (proto/dcs/proto_json.h)
// each atomically (common/atomic_file.h), rewritten after every evaluation so a running run can
// be watched; and read back (ReadEvaluationLog: the one reader of evaluations.json, and of the
// log the coordinator appends to, run/appended_evaluation_log.h).
// Thread-safe (pure functions).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "actor/evaluation.h"
#include "actor/split.h"
#include "dcs/v1/evaluation.pb.h"
#include "run/run_spec.h"

namespace dcs::run {

// The log of `evaluations` of the run `spec`. `complete`: the last evaluation is the one at the
// end of training. Best-anytime is the highest avg_combined; with `stage_boundaries` (a
// multi-stage run) only evaluations at a boundary or the end are candidates.
v1::EvaluationLog MakeEvaluationLog(const RunSpec& spec,
                                    const std::vector<actor::EvaluationResult>& evaluations,
                                    const std::vector<int64_t>& stage_boundaries, bool complete);

// evaluations.csv in `dir`, for people to open.
std::string EvaluationCsvPath(const std::string& dir);

// One file of an evaluation log: its name in the run's directory and its contents.
struct EvaluationLogFile {
  std::string name;
  std::string contents;
};

// evaluations.csv and evaluations.json of `log`, as WriteEvaluationLog writes them.
// REQUIRES: as WriteEvaluationLog.
std::vector<EvaluationLogFile> EvaluationLogFiles(const v1::EvaluationLog& log);

// Writes evaluations.csv and evaluations.json into `dir`. Errors name the file
// (RESOURCE_EXHAUSTED for a full disk); a file that fails keeps its previous contents.
// REQUIRES: every context has a split, as logs from MakeEvaluationLog and ReadEvaluationLog do.
absl::Status WriteEvaluationLog(const std::string& dir, const v1::EvaluationLog& log);

// The evaluation log in `dir`: the one appended there (run/appended_evaluation_log.h) if there
// is one, else evaluations.json. NOT_FOUND if it has none; DATA_LOSS naming the file if that is
// not an evaluation log (not JSON, an unknown field, a context of no known split).
absl::StatusOr<v1::EvaluationLog> ReadEvaluationLog(const std::string& dir);

// A split as the proto numbers it, and back: nullopt for SPLIT_UNSPECIFIED and values no split
// has. The numbers are the C++ enumeration's plus one (checked where they are converted).
v1::Split SplitToProto(actor::Split split);
std::optional<actor::Split> SplitFromProto(int split);

namespace internal {

// OK if every context of `evaluation`, read from `path`, is of a known split; DATA_LOSS naming
// the file, the evaluation's step and the split otherwise. For the log's two readers.
absl::Status CheckSplits(const v1::Evaluation& evaluation, const std::string& path);

}  // namespace internal

}  // namespace dcs::run

#endif  // DCS_RUN_EVALUATION_LOG_H_
