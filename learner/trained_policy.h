// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_TRAINED_POLICY_H_
#define DCS_LEARNER_TRAINED_POLICY_H_

// A trained policy as a run's directory keeps it (run/run_directory.h, run/run_checkpoint.h):
// the run's spec and one checkpoint's learner, loaded. What `dcs eval`, `dcs play` and
// `dcs export` start from. Thread-compatible.

#include <cstdint>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "learner/ppo_learner.h"
#include "run/ppo_config.h"
#include "run/run_checkpoint.h"
#include "run/run_directory.h"
#include "run/run_plan.h"

namespace dcs::learner {

struct TrainedPolicy {
  run::RunRequest run;  // its spec, config text and directory
  run::RunPlan plan;
  run::PolicySpec policy;         // the network's shapes
  std::string checkpoint_path;    // the checkpoint's directory, for messages
  int64_t step = 0;               // environment steps of training it holds
  run::RunState state;            // its counters and evaluations
  std::unique_ptr<PpoLearner> learner;
};

// The policy of `run` at its initial weights (seeded as training seeds them): its plan and
// network shapes, and a new learner. INVALID_ARGUMENT as run::PlanRun for an invalid spec.
absl::StatusOr<TrainedPolicy> NewTrainedPolicy(run::RunRequest run);

// The policy of run directory `run_dir` at checkpoint `which`: "last" (the one the run's
// `latest` names); "best", of the kept checkpoints the one whose policy scores the highest
// avg_combined on the run's own evaluation protocol (as the run's log has it for a policy the
// run evaluated, the protocol being deterministic; others evaluated here); or a step, one of
// the kept checkpoints'. Read strictly: a corrupt checkpoint is an error, never replaced by an
// older one.
// NOT_FOUND naming the directory if it holds no run, or naming the kept checkpoints if none is
// at that step; INVALID_ARGUMENT for `which` neither "last" nor a step; DATA_LOSS naming the
// file of a checkpoint that is corrupt or does not load into the run's network.
absl::StatusOr<TrainedPolicy> LoadTrainedPolicy(const std::string& run_dir,
                                                absl::string_view which);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_TRAINED_POLICY_H_
