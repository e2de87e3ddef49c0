// Copyright 2026 The DCS Authors.
#include "run/ppo_config.h"

#include <cmath>
#include <set>
#include <string>

#include "absl/strings/str_cat.h"
#include "run/config_keys.h"

namespace dcs::run {

const KeyTable<PpoConfig>& PpoConfigKeys() {
  using P = PpoConfig;
  static const KeyTable<P>* const keys = new KeyTable<P>({
      {.name = "learning_rate",
       .meaning = "Adam's step size, constant over the run",
       .field = &P::learning_rate,
       .bound = Positive()},
      {.name = "n_steps",
       .meaning = "transitions collected per environment per rollout (n_steps * n_envs > 1)",
       .field = &P::n_steps,
       .bound = AtLeast(1)},
      {.name = "batch_size",
       .meaning = "transitions per minibatch (more than 1 with normalize_advantage)",
       .field = &P::batch_size,
       .bound = AtLeast(1)},
      {.name = "n_epochs",
       .meaning = "passes over each rollout",
       .field = &P::n_epochs,
       .bound = AtLeast(1)},
      {.name = "gamma", .meaning = "discount factor", .field = &P::gamma, .bound = Within(0, 1)},
      {.name = "gae_lambda",
       .meaning = "GAE's lambda: bias against variance of the advantages",
       .field = &P::gae_lambda,
       .bound = Within(0, 1)},
      {.name = "clip_range",
       .meaning = "how far the probability ratio may move from 1 before it is clipped",
       .field = &P::clip_range,
       .bound = Positive()},
      {.name = "clip_range_vf",
       .meaning = "how far the value may move from its old prediction; null: not clipped",
       .field = &P::clip_range_vf,
       .bound = Positive()},
      {.name = "normalize_advantage",
       .meaning = "advantages normalised per minibatch",
       .field = &P::normalize_advantage},
      {.name = "ent_coef",
       .meaning = "weight of the entropy bonus in the loss",
       .field = &P::ent_coef,
       .bound = AtLeast(0)},
      {.name = "vf_coef",
       .meaning = "weight of the value loss in the loss",
       .field = &P::vf_coef,
       .bound = AtLeast(0)},
      {.name = "max_grad_norm",
       .meaning = "gradients clipped to this global norm",
       .field = &P::max_grad_norm,
       .bound = Positive()},
      {.name = "target_kl",
       .meaning = "an update's epochs stop once the approximate KL exceeds 1.5 times it; null: "
                  "never",
       .field = &P::target_kl,
       .bound = Positive()},
      {.name = "pi_layers",
       .meaning = "hidden widths of the actor's MLP (tanh)",
       .field = &P::pi_layers,
       .bound = Positive(),
       .items = "widths"},
      {.name = "vf_layers",
       .meaning = "hidden widths of the critic's MLP (tanh)",
       .field = &P::vf_layers,
       .bound = Positive(),
       .items = "widths"},
      {.name = "log_std_init",
       .meaning = "initial log standard deviation of a continuous action (diagonal Gaussian)",
       .field = &P::log_std_init},
      {.name = "adam_eps", .meaning = "Adam's epsilon", .field = &P::adam_eps, .bound = Positive()},
      {.name = "cnn_features",
       .meaning = "NatureCNN's output features, for image observations",
       .field = &P::cnn_features,
       .bound = AtLeast(1)},
      {.name = "context_layers",
       .meaning = "an image policy's MLP over its observed context (ReLU); []: the context "
                  "joins NatureCNN's features as it is",
       .field = &P::context_layers,
       .bound = Positive(),
       .items = "widths"},
  });
  return *keys;
}

void CheckPpoConfig(const PpoConfig& c, int n_envs, const ConfigErrors& errors,
                    ConfigProblems& problems) {
  const std::set<absl::string_view> named =
      CheckBounds(PpoConfigKeys(), c, "ppo", errors, problems);
  auto check = [&](bool ok, absl::string_view name, absl::string_view rule, double value) {
    if (ok || named.contains(name)) return;
    problems.Add(errors.At(KeyPath("ppo", name), absl::StrCat("must be ", rule, ", got ", value)));
  };
  check(!c.normalize_advantage || c.batch_size > 1, "batch_size",
        "greater than 1 when advantages are normalised", c.batch_size);
  check(n_envs < 1 || static_cast<int64_t>(c.n_steps) * n_envs > 1, "n_steps",  // n_envs's own
        "such that n_steps * n_envs > 1", static_cast<double>(c.n_steps) * n_envs);
}

absl::Status ValidatePpoConfig(const PpoConfig& c, int n_envs, const ConfigErrors& errors) {
  ConfigProblems problems;
  CheckPpoConfig(c, n_envs, errors, problems);
  return problems.ToStatus(errors.where());
}

absl::Status ValidatePolicySpec(const PolicySpec& s) {
  if (s.observation_size < 0 || s.context_size < 0 ||
      (s.observation_size == 0 && !s.has_image())) {
    return absl::InvalidArgumentError("a policy needs an observation");
  }
  if (s.has_image() && (s.image_width < 1 || s.image_channels < 1)) {
    return absl::InvalidArgumentError("an image observation needs a width and channels");
  }
  if (s.discrete()) {
    if (s.action_size != 1) {
      return absl::InvalidArgumentError("a discrete action is one index (action_size 1)");
    }
  } else if (s.action_size < 1 || s.action_low.size() != static_cast<size_t>(s.action_size) ||
             s.action_high.size() != static_cast<size_t>(s.action_size)) {
    return absl::InvalidArgumentError(
        "a continuous action needs action_size > 0 and low and high bounds of that size");
  }
  return absl::OkStatus();
}

}  // namespace dcs::run
