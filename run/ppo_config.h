// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_PPO_CONFIG_H_
#define DCS_RUN_PPO_CONFIG_H_

// PPO's hyperparameters, defaulting to Stable-Baselines3's (ppo/ppo.py, common/policies.py), which
// the paper used untuned; and the shape of the policy a learner trains. Thread-safe (plain data).

#include <cstddef>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "run/config_errors.h"

namespace dcs::run {

struct PpoConfig {
  double learning_rate = 3e-4;  // constant
  int n_steps = 2048;           // transitions per environment per rollout
  int batch_size = 64;
  int n_epochs = 10;
  double gamma = 0.99;
  double gae_lambda = 0.95;
  double clip_range = 0.2;
  std::optional<double> clip_range_vf;  // none: no value clipping
  bool normalize_advantage = true;      // per minibatch
  double ent_coef = 0.0;
  double vf_coef = 0.5;
  double max_grad_norm = 0.5;
  std::optional<double> target_kl;  // none: no early stop
  std::vector<int> pi_layers = {64, 64};  // actor MLP, tanh
  std::vector<int> vf_layers = {64, 64};  // critic MLP, tanh
  double log_std_init = 0.0;              // diagonal Gaussian, state-independent
  double adam_eps = 1e-5;
  int cnn_features = 256;  // NatureCNN output for image observations (CombinedExtractor)
  // An image policy that observes its context: the context's own MLP (ReLU after each layer),
  // whose output joins NatureCNN's features, as the paper describes its CarRacing policy.
  // Empty: the context joins as it is (SB3's CombinedExtractor). A policy without image or
  // without context has no such branch.
  std::vector<int> context_layers;
};

template <typename S>
class KeyTable;

// The keys of a run config's `ppo` mapping (run/config_keys.h), in the order the run config's
// reader lists them: each field of PpoConfig with its bound and meaning, which the reader, the
// check below and docs/config.md take from it.
const KeyTable<PpoConfig>& PpoConfigKeys();

// Adds to `problems` each field of `config` out of range, by its path in a run config
// (`ppo.gamma`): first each field outside its bound in PpoConfigKeys(), then SB3's guards
// between fields (batch_size > 1 with advantage normalisation, n_steps * n_envs > 1), through
// `errors` (with the config's file and line when read from one); a field is named once, by the
// first of its rules it breaks (n_steps * n_envs only with n_envs >= 1: a smaller n_envs is the
// run config's problem).
void CheckPpoConfig(const PpoConfig& config, int n_envs, const ConfigErrors& errors,
                    ConfigProblems& problems);
// OK, or INVALID_ARGUMENT with CheckPpoConfig's problems (run/config_errors.h: ConfigProblems).
absl::Status ValidatePpoConfig(const PpoConfig& config, int n_envs,
                               const ConfigErrors& errors = ConfigErrors());

// What the policy sees and does.
struct PolicySpec {
  int observation_size = 0;  // a flat float vector; 0 with an image
  // An image observation (uint8, height x width x channels, channel last), or none.
  int image_height = 0;
  int image_width = 0;
  int image_channels = 0;
  int context_size = 0;  // normalised context values appended (0 when blind)
  // Discrete: num_actions > 0 and action_size 1; continuous: num_actions 0 and action_size > 0
  // with the bounds the environment clips to.
  int num_actions = 0;
  int action_size = 1;
  std::vector<float> action_low;
  std::vector<float> action_high;

  bool discrete() const { return num_actions > 0; }
  // Outputs of the policy's action head: logits, or the Gaussian's means.
  int head_size() const { return discrete() ? num_actions : action_size; }
  bool has_image() const { return image_height > 0; }
  // Bytes of one image observation; 0 without.
  size_t image_size() const {
    return static_cast<size_t>(image_height) * image_width * image_channels;
  }
  // Floats per observation given to the MLP: the vector observation, then the context.
  int flat_input_size() const { return observation_size + context_size; }
};

// INVALID_ARGUMENT for an inconsistent spec.
absl::Status ValidatePolicySpec(const PolicySpec& spec);

}  // namespace dcs::run

#endif  // DCS_RUN_PPO_CONFIG_H_
