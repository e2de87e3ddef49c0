// Copyright 2026 The DCS Authors.
#include "learner/trained_policy.h"

#include <optional>
#include <utility>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "actor/evaluation.h"
#include "actor/policy_network.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "env/env_registry.h"

namespace dcs::learner {
namespace {

// The run of `run_dir`, resolved against its environment, with an untrained learner.
absl::StatusOr<TrainedPolicy> OpenRun(const std::string& run_dir) {
  absl::StatusOr<run::RunRequest> request = run::StoredRun(run_dir);
  if (absl::IsNotFound(request.status())) {
    return absl::NotFoundError(absl::StrCat("no run in ", run_dir, " (no config.yaml)"));
  }
  DCS_RETURN_IF_ERROR(request.status());
  return NewTrainedPolicy(*std::move(request));
}

// `trained` with checkpoint `name` of its run loaded into its learner.
absl::Status LoadCheckpoint(const std::string& name, TrainedPolicy& trained) {
  trained.checkpoint_path = absl::StrCat(trained.run.dir, "/checkpoints/", name);
  DCS_ASSIGN_OR_RETURN(run::Checkpoint checkpoint, run::ReadCheckpoint(trained.run.dir, name));
  if (absl::Status loaded = trained.learner->LoadState(checkpoint.learner); !loaded.ok()) {
    return absl::DataLossError(
        absl::StrCat(trained.checkpoint_path, "/learner.bin: ", loaded.message()));
  }
  trained.step = checkpoint.state.timesteps;
  trained.state = std::move(checkpoint.state);
  return absl::OkStatus();
}

// avg_combined of `trained`'s policy on its run's evaluation protocol: as its checkpoint
// records it if the run evaluated that policy version (the protocol is deterministic, so that is
// what evaluating it again gives), else evaluated here.
absl::StatusOr<double> ProtocolScore(const TrainedPolicy& trained) {
  for (const actor::EvaluationResult& evaluation : trained.state.evaluations) {
    if (evaluation.updates == trained.learner->updates()) return evaluation.avg_combined;
  }
  DCS_ASSIGN_OR_RETURN(actor::PolicyNetwork policy,
                       actor::PolicyNetwork::Create(trained.learner->ActorWeights()));
  double score = 0;
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(trained.run.spec.env, [&]<typename Env>() {
    DCS_ASSIGN_OR_RETURN(
        const actor::EvaluationResult result,
        actor::Evaluate<Env>(policy, trained.plan.slot, trained.plan.feature,
                             trained.plan.evaluation_contexts, trained.run.spec.eval_episodes,
                             trained.run.spec.seed));
    score = result.avg_combined;
    return absl::OkStatus();
  }));
  return score;
}

}  // namespace

absl::StatusOr<TrainedPolicy> NewTrainedPolicy(run::RunRequest run) {
  TrainedPolicy trained{.run = std::move(run)};
  const run::RunSpec& spec = trained.run.spec;
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(spec.env, [&]<typename Env>() {
    DCS_ASSIGN_OR_RETURN(trained.plan, run::PlanRun(spec, Env::Features()));
    trained.policy =
        run::PolicySpecFor<Env>(static_cast<int>(trained.plan.slot.observed_features.size()));
    return absl::OkStatus();
  }));
  DCS_ASSIGN_OR_RETURN(trained.learner,
                       PpoLearner::Create(trained.policy, spec.ppo, spec.n_envs, spec.seed));
  return trained;
}

absl::StatusOr<TrainedPolicy> LoadTrainedPolicy(const std::string& run_dir,
                                                absl::string_view which) {
  DCS_ASSIGN_OR_RETURN(TrainedPolicy trained, OpenRun(run_dir));
  DCS_ASSIGN_OR_RETURN(const std::vector<std::string> names, run::CheckpointNames(run_dir));
  if (names.empty()) return absl::NotFoundError(absl::StrCat("no checkpoint in ", run_dir));
  if (which == "last") {
    DCS_RETURN_IF_ERROR(LoadCheckpoint(names.back(), trained));
    return trained;
  }
  if (which == "best") {
    std::optional<std::pair<double, std::string>> best;
    for (const std::string& name : names) {
      DCS_RETURN_IF_ERROR(LoadCheckpoint(name, trained));
      DCS_ASSIGN_OR_RETURN(const double score, ProtocolScore(trained));
      if (!best.has_value() || score > best->first) best.emplace(score, name);
    }
    if (best->second != names.back()) DCS_RETURN_IF_ERROR(LoadCheckpoint(best->second, trained));
    return trained;
  }
  int64_t step = 0;
  if (!absl::SimpleAtoi(which, &step) || step < 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "--checkpoint '", which, "' is neither last, best nor a step"));
  }
  const std::string name = run::CheckpointName(step);
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::vector<int64_t> kept;
    for (const std::string& kept_name : names) {
      int64_t kept_step = 0;
      if (absl::SimpleAtoi(kept_name, &kept_step)) kept.push_back(kept_step);
    }
    return absl::NotFoundError(absl::StrCat("no checkpoint at step ", step, " in ", run_dir,
                                            " (kept: ", absl::StrJoin(kept, ", "), ")"));
  }
  DCS_RETURN_IF_ERROR(LoadCheckpoint(name, trained));
  return trained;
}

}  // namespace dcs::learner
