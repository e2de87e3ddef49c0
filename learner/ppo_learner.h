// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_PPO_LEARNER_H_
#define DCS_LEARNER_PPO_LEARNER_H_

// PPO as Stable-Baselines3 implements it (stable_baselines3/ppo/ppo.py), behind a torch-free
// interface: Update() takes one rollout, computes values and log-probabilities of the collected
// actions, bootstraps time-limit cuts, runs GAE, then n_epochs of minibatch updates (advantages
// normalised per minibatch, clipped surrogate, unclipped MSE value loss, entropy bonus, global
// gradient-norm clipping, Adam with eps 1e-5). The parameters and Adam's state are libtorch's; the
// passes are Eigen products on them (learner/actor_critic.h, learner/nature_cnn.h).
//
// Deterministic: initial weights come from StreamSeed(seed, "init") and minibatch orders from
// StreamSeed(seed, "minibatch", {update, epoch}); with libtorch pinned to one thread and the
// numeric kernels pinned (learner/torch_runtime.h, actor/eigen_blocking.h) the same seed and
// rollouts give the same weights bit for bit on every x86-64-v3 machine, whatever other
// learners do at the same time on other threads. Each learner is confined to one thread at a
// time.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "actor/policy_weights.h"
#include "actor/rollout.h"
#include "run/ppo_config.h"

namespace dcs::learner {

// The keys of the Dict observation of an image policy's Stable-Baselines3 equivalent
// (MultiInputPolicy; Sb3StateDict). gymnasium sorts a Dict's keys and CombinedExtractor
// concatenates its features in that order: these sort as DCS concatenates, image first.
inline constexpr absl::string_view kSb3ImageKey = "image";
inline constexpr absl::string_view kSb3ContextKey = "observed_context";

// Means over every minibatch of the update, as SB3 logs them.
struct UpdateStats {
  double policy_loss = 0;
  double value_loss = 0;
  double entropy_loss = 0;
  double approx_kl = 0;
  double clip_fraction = 0;
  double loss = 0;  // of the last minibatch, as SB3 logs it
  double explained_variance = 0;
  // A Gaussian policy's mean of exp(log_std) after the update; nullopt for a categorical one.
  std::optional<double> std;
  // The gradient's global norm before clipping (what clip_grad_norm_ returns), mean over the
  // gradient steps; 0 if none was taken (target_kl stopped the first minibatch).
  double grad_norm = 0;
  double learning_rate = 0;  // Adam's, as the update applied it
  int gradient_steps = 0;
  bool stopped_early = false;  // target_kl reached
};

class PpoLearner final {
 public:
  // INVALID_ARGUMENT for an invalid spec or config.
  static absl::StatusOr<std::unique_ptr<PpoLearner>> Create(const run::PolicySpec& spec,
                                                           const run::PpoConfig& config, int n_envs,
                                                           uint64_t seed);
  ~PpoLearner();
  PpoLearner(const PpoLearner&) = delete;
  PpoLearner& operator=(const PpoLearner&) = delete;

  // Learns from one rollout. INVALID_ARGUMENT if its shapes do not fit the spec, config and
  // n_envs, or an input or reward is not finite (naming the step and slot): the weights are
  // untouched. INTERNAL if the loss becomes non-finite; that minibatch is not applied.
  absl::StatusOr<UpdateStats> Update(const actor::Rollout& rollout);

  // The number of updates so far: the policy version.
  int64_t updates() const;

  // The actor network, for Eigen inference (actor/policy_network.h).
  actor::PolicyWeights ActorWeights() const;

  // The value estimates of `count` observations: `inputs` their flat inputs (count *
  // flat_input_size floats) and `images` their images (count * image_size bytes), as rollouts
  // carry them. REQUIRES: those sizes.
  std::vector<float> Values(std::span<const float> inputs, std::span<const uint8_t> images,
                            int count) const;

  // The weights as the bytes of a PyTorch state dict (torch.load reads them: a dict of float32
  // tensors) under Stable-Baselines3's names, so that its policy of the same architecture
  // takes them with load_state_dict(strict=True): MlpPolicy's, or for image policies
  // MultiInputPolicy's with the Dict keys kSb3ImageKey and kSb3ContextKey. The context
  // branch (PpoConfig::context_layers) has no SB3 counterpart: it is the extractor's
  // extractors.<kSb3ContextKey> Sequential (Linear, ReLU, ...). INTERNAL if libtorch fails.
  absl::StatusOr<std::string> Sb3StateDict() const;

  // Every parameter, flattened in a fixed order (tests compare runs with it).
  std::vector<float> Parameters() const;

  // Weights, optimiser state, the update count and the seed, as bytes; and back. Load:
  // DATA_LOSS if the bytes are corrupt or hold a different network; FAILED_PRECONDITION if they
  // come from a learner with another seed (its minibatch orders would differ).
  absl::StatusOr<std::string> SaveState() const;
  absl::Status LoadState(absl::string_view bytes);

 private:
  struct Impl;
  explicit PpoLearner(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace dcs::learner

#endif  // DCS_LEARNER_PPO_LEARNER_H_
