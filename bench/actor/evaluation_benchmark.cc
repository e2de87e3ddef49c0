// Copyright 2026 The DCS Authors.
//
// One evaluation of a trained policy with the run's protocol (actor::Evaluate: every evaluation
// context, its episodes deterministic and seeded as in training): the figure issue 32 asks to
// halve, for the paper's CartPole config 15 contexts x 30 episodes, about 180k environment
// steps with this policy. The policy is the latest checkpoint of a run directory that
// `dcs train` wrote, named by DCS_BENCH_RUN_DIR, for example
//   dcs train configs/cartpole_length_pool7_static_blind.yaml --out /tmp/trained
//   DCS_BENCH_RUN_DIR=/tmp/trained build/bench/actor/actor_evaluation_benchmark
// Counters: environment steps per second, and the evaluation's avg_combined (the same run dir
// gives the same figure whatever the machine).

#include <cstdlib>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "actor/evaluation.h"
#include "actor/policy_network.h"
#include "benchmark/benchmark.h"
#include "env/env_registry.h"
#include "learner/ppo_learner.h"
#include "learner/torch_runtime.h"
#include "run/run_checkpoint.h"
#include "run/run_directory.h"
#include "run/run_plan.h"

namespace dcs::actor {
namespace {

// The run of DCS_BENCH_RUN_DIR and its latest policy, or why not.
struct TrainedRun {
  run::RunSpec spec;
  PolicyWeights weights;
};

template <typename Env>
absl::StatusOr<TrainedRun> LoadTrainedRun(const std::string& dir) {
  DCS_ASSIGN_OR_RETURN(run::RunRequest stored, run::StoredRun(dir));
  DCS_ASSIGN_OR_RETURN(const run::Checkpoint checkpoint, run::ReadLatestCheckpoint(dir));
  DCS_ASSIGN_OR_RETURN(const run::RunPlan plan, run::PlanRun(stored.spec, Env::Features()));
  DCS_ASSIGN_OR_RETURN(
      std::unique_ptr<learner::PpoLearner> learner,
      learner::PpoLearner::Create(
          run::PolicySpecFor<Env>(static_cast<int>(plan.slot.observed_features.size())),
          stored.spec.ppo, stored.spec.n_envs, stored.spec.seed));
  DCS_RETURN_IF_ERROR(learner->LoadState(checkpoint.learner));
  return TrainedRun{.spec = std::move(stored.spec), .weights = learner->ActorWeights()};
}

template <typename Env>
void Run(benchmark::State& state, const TrainedRun& trained) {
  absl::StatusOr<run::RunPlan> plan = run::PlanRun(trained.spec, Env::Features());
  absl::StatusOr<PolicyNetwork> policy = PolicyNetwork::Create(trained.weights);
  if (!plan.ok() || !policy.ok()) {
    state.SkipWithError((plan.ok() ? policy.status() : plan.status()).ToString().c_str());
    return;
  }
  double steps = 0;
  double avg_combined = 0;
  for (auto _ : state) {
    absl::StatusOr<EvaluationResult> result =
        Evaluate<Env>(*policy, plan->slot, plan->feature, plan->evaluation_contexts,
                      trained.spec.eval_episodes, trained.spec.seed);
    if (!result.ok()) {
      state.SkipWithError(result.status().ToString().c_str());
      return;
    }
    for (const ContextResult& context : result->contexts) {
      for (double episode_return : context.returns) steps += episode_return;  // reward 1 a step
    }
    avg_combined = result->avg_combined;
  }
  state.counters["avg_combined"] = avg_combined;
  if (trained.spec.env == "cartpole") {
    state.counters["steps_per_s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  }
}

void BM_EvaluateTrainedPolicy(benchmark::State& state) {
  learner::PinTorchThreads(1).IgnoreError();
  const char* dir = std::getenv("DCS_BENCH_RUN_DIR");
  if (dir == nullptr) {
    state.SkipWithError("set DCS_BENCH_RUN_DIR to a run directory that dcs train wrote");
    return;
  }
  absl::StatusOr<run::RunRequest> stored = run::StoredRun(dir);
  if (!stored.ok()) {
    state.SkipWithError(stored.status().ToString().c_str());
    return;
  }
  const absl::Status status =
      env::VisitEnvironment(stored->spec.env, [&]<typename Env>() -> absl::Status {
        DCS_ASSIGN_OR_RETURN(const TrainedRun trained, LoadTrainedRun<Env>(dir));
        Run<Env>(state, trained);
        return absl::OkStatus();
      });
  if (!status.ok()) state.SkipWithError(status.ToString().c_str());
}
BENCHMARK(BM_EvaluateTrainedPolicy)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dcs::actor
