// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_EVALUATION_LOG_H_
#define DCS_LEARNER_EVALUATION_LOG_H_

// A run's evaluation log: its evaluations in order with the paper's two per-run scores, last and
// best-anytime (spec/schedules.md §9.3), written to the run's output directory as
//   evaluations.csv   one row per evaluation and context:
//                     step,updates,split,value,episodes,mean,std,seconds
//   evaluations.json  a dcs.v1.EvaluationLog (proto/dcs/v1/evaluation.proto) as JSON
//                     (proto/dcs/proto_json.h)
// each atomically (common/atomic_file.h), rewritten after every evaluation so a running run can
// be watched. Thread-safe (pure functions).

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "actor/evaluation.h"
#include "dcs/v1/evaluation.pb.h"
#include "learner/run_spec.h"

namespace dcs::learner {

// The log of `evaluations` of the run `spec`. `complete`: the last evaluation is the one at the
// end of training. Best-anytime is the highest avg_combined; with `stage_boundaries` (a
// multi-stage run) only evaluations at a boundary or the end are candidates (§8).
v1::EvaluationLog MakeEvaluationLog(const RunSpec& spec,
                                    const std::vector<actor::EvaluationResult>& evaluations,
                                    const std::vector<int64_t>& stage_boundaries, bool complete);

// Writes evaluations.csv and evaluations.json into `dir`. Errors name the file
// (RESOURCE_EXHAUSTED for a full disk); a file that fails keeps its previous contents.
absl::Status WriteEvaluationLog(const std::string& dir, const v1::EvaluationLog& log);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_EVALUATION_LOG_H_
