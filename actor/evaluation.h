// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_EVALUATION_H_
#define DCS_ACTOR_EVALUATION_H_

// The paper's evaluation protocol (docs/reference.md, "Evaluation protocol"): the deterministic
// policy on static contexts (no pool, no schedule) in three splits, ID, OOD-low and OOD-high, a
// fixed number of episodes per context; per context the mean and standard deviation of the episode
// return; per split the mean and the minimum of the context means; avg_combined, the mean of every
// context's mean. Episode i of context c resets from StreamSeed(seed, "eval", {c}) and i whatever
// the checkpoint or worker, so every evaluation of a run sees the same episodes. Thread-compatible.

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "actor/policy.h"
#include "actor/rollout_collector.h"
#include "actor/split.h"
#include "common/random.h"
#include "common/status_macros.h"
#include "env/dynamic_context_env.h"

namespace dcs::actor {

struct EvaluationContext {
  Split split = Split::kId;
  double value = 0;  // the varied feature's value
};

struct ContextResult {
  EvaluationContext context;
  double mean = 0;
  double std = 0;  // population standard deviation over the episodes
  std::vector<double> returns;
  double seconds = 0;
};

struct EvaluationResult {
  int64_t step = 0;     // environment steps of training when evaluated
  int64_t updates = 0;  // PPO updates the evaluated policy had had (its version)
  std::vector<ContextResult> contexts;
  // Per split, the mean and minimum of its contexts' means (NaN for a split without contexts).
  double split_mean[kNumSplits] = {0, 0, 0};
  double split_min[kNumSplits] = {0, 0, 0};
  double avg_combined = 0;  // the mean over every context
};

// Fills `result`'s mean and std from its returns.
void SummarizeContext(ContextResult& result);

// Fills the summary (per-context mean and std; split means and minima; avg_combined) of
// `result` from its contexts' returns.
void Summarize(EvaluationResult& result);

// Runs the protocol for `Env`: `base` gives the context, observation mode and observed features
// (its pools and schedules are ignored); `feature` is set to each evaluation value.
// INVALID_ARGUMENT if an evaluation value is not valid for the feature.
template <typename Env>
absl::StatusOr<EvaluationResult> Evaluate(Policy& policy, const env::DynamicContextOptions& base,
                                          int feature,
                                          const std::vector<EvaluationContext>& contexts,
                                          int episodes, uint64_t seed);

// The episodes of context number `index` of a run's evaluation contexts, `context`: one job of
// Evaluate, the same returns wherever it runs (an actor evaluates contexts one at a time).
// Its mean and std are left to Summarize.
template <typename Env>
absl::StatusOr<ContextResult> EvaluateContext(Policy& policy,
                                              const env::DynamicContextOptions& base, int feature,
                                              const EvaluationContext& context, size_t index,
                                              int episodes, uint64_t seed);

// Implementation details.

inline void SummarizeContext(ContextResult& result) {
  double sum = 0;
  for (double value : result.returns) sum += value;
  result.mean = sum / static_cast<double>(result.returns.size());
  double squares = 0;
  for (double value : result.returns) squares += (value - result.mean) * (value - result.mean);
  result.std = std::sqrt(squares / static_cast<double>(result.returns.size()));
}

inline void Summarize(EvaluationResult& result) {
  double combined = 0;
  for (ContextResult& r : result.contexts) {
    SummarizeContext(r);
    combined += r.mean;
  }
  for (int split = 0; split < kNumSplits; ++split) {
    double sum = 0;
    double minimum = std::numeric_limits<double>::infinity();
    int count = 0;
    for (const ContextResult& r : result.contexts) {
      if (static_cast<int>(r.context.split) != split) continue;
      sum += r.mean;
      minimum = std::min(minimum, r.mean);
      ++count;
    }
    result.split_mean[split] = count > 0 ? sum / count : std::nan("");
    result.split_min[split] = count > 0 ? minimum : std::nan("");
  }
  result.avg_combined = combined / static_cast<double>(result.contexts.size());
}

template <typename Env>
absl::StatusOr<ContextResult> EvaluateContext(Policy& policy,
                                              const env::DynamicContextOptions& base, int feature,
                                              const EvaluationContext& context, size_t index,
                                              int episodes, uint64_t seed) {
  constexpr int kObs = Env::kObservationSize;
  constexpr int kAct = Env::kActionSize;
  const auto start = std::chrono::steady_clock::now();
  env::DynamicContextOptions options{
      .context = base.context,
      .observe = base.observe,
      .observed_features = base.observed_features,
      .run_seed = StreamSeed(seed, "eval", {index}).GenerateState64(1)[0]};
  if (options.context.empty()) options.context = Env::Features().Defaults();
  options.context[feature] = context.value;
  // One environment per episode, all stepped together: environment e plays episode e of the
  // context's stream, as it would were the episodes played one after another.
  std::vector<env::DynamicContextEnv<Env>> environments;
  environments.reserve(episodes);
  for (int e = 0; e < episodes; ++e) {
    DCS_ASSIGN_OR_RETURN(env::DynamicContextEnv<Env> environment,
                         env::DynamicContextEnv<Env>::Create(options));
    environment.SetNextEpisode(e);
    environments.push_back(std::move(environment));
  }
  const size_t context_size = episodes > 0 ? environments.front().context_size() : 0;
  std::vector<typename Env::Observation> observations(static_cast<size_t>(episodes) * kObs);
  std::vector<float> contexts(episodes * context_size);
  const auto observation_of = [&](int e) {
    return std::span<typename Env::Observation, kObs>(observations.data() + e * kObs, kObs);
  };
  const auto context_of = [&](int e) {
    return std::span<float>(contexts).subspan(e * context_size, context_size);
  };
  for (int e = 0; e < episodes; ++e) environments[e].Reset(0, observation_of(e), context_of(e));

  ContextResult result{.context = context, .returns = std::vector<double>(episodes, 0.0)};
  std::vector<int> running(episodes);  // the episodes not yet done, in order
  std::iota(running.begin(), running.end(), 0);
  std::vector<float> inputs;
  std::vector<uint8_t> images;
  std::vector<float> actions;
  std::array<typename Env::ActionElement, kAct> env_action;
  while (!running.empty()) {
    inputs.clear();
    images.clear();
    for (int e : running) {
      AppendPolicyInput<Env>(observation_of(e), context_of(e), inputs, images);
    }
    actions.resize(running.size() * kAct);
    policy.Act(static_cast<int>(running.size()), inputs, images, /*deterministic=*/true,
               /*randoms=*/{}, actions);
    size_t still_running = 0;
    for (size_t k = 0; k < running.size(); ++k) {
      const int e = running[k];
      ToEnvAction<Env>(std::span<const float>(actions).subspan(k * kAct, kAct), env_action);
      const env::StepResult step =
          environments[e].Step(env_action, observation_of(e), context_of(e));
      result.returns[e] += step.reward;
      if (!step.done()) running[still_running++] = e;
    }
    running.resize(still_running);
  }
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

template <typename Env>
absl::StatusOr<EvaluationResult> Evaluate(Policy& policy, const env::DynamicContextOptions& base,
                                          int feature,
                                          const std::vector<EvaluationContext>& contexts,
                                          int episodes, uint64_t seed) {
  EvaluationResult result;
  for (size_t c = 0; c < contexts.size(); ++c) {
    DCS_ASSIGN_OR_RETURN(ContextResult context,
                         EvaluateContext<Env>(policy, base, feature, contexts[c], c, episodes,
                                              seed));
    result.contexts.push_back(std::move(context));
  }
  Summarize(result);
  return result;
}

}  // namespace dcs::actor

#endif  // DCS_ACTOR_EVALUATION_H_
