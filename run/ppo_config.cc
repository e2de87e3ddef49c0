// Copyright 2026 The DCS Authors.
#include "run/ppo_config.h"

#include <cmath>
#include <functional>
#include <set>
#include <string>

#include "absl/strings/str_cat.h"

namespace dcs::run {

void CheckPpoConfig(const PpoConfig& c, int n_envs, const ConfigErrors& errors,
                    ConfigProblems& problems) {
  std::set<std::string, std::less<>> named;  // fields with a problem already
  auto check = [&](bool ok, absl::string_view name, absl::string_view rule, double value) {
    if (ok || !named.emplace(name).second) return;
    problems.Add(errors.At(KeyPath("ppo", name), absl::StrCat("must be ", rule, ", got ", value)));
  };
  check(c.learning_rate > 0 && std::isfinite(c.learning_rate), "learning_rate",
        "positive", c.learning_rate);
  check(c.n_steps >= 1, "n_steps", "at least 1", c.n_steps);
  check(c.batch_size >= 1, "batch_size", "at least 1", c.batch_size);
  check(!c.normalize_advantage || c.batch_size > 1, "batch_size",
        "greater than 1 when advantages are normalised", c.batch_size);
  check(n_envs < 1 || static_cast<int64_t>(c.n_steps) * n_envs > 1, "n_steps",  // n_envs's own
        "such that n_steps * n_envs > 1", static_cast<double>(c.n_steps) * n_envs);
  check(c.n_epochs >= 1, "n_epochs", "at least 1", c.n_epochs);
  check(c.gamma >= 0 && c.gamma <= 1, "gamma", "in [0, 1]", c.gamma);
  check(c.gae_lambda >= 0 && c.gae_lambda <= 1, "gae_lambda", "in [0, 1]",
        c.gae_lambda);
  check(c.clip_range > 0, "clip_range", "positive", c.clip_range);
  check(!c.clip_range_vf.has_value() || *c.clip_range_vf > 0, "clip_range_vf",
        "positive", c.clip_range_vf.value_or(0));
  check(c.ent_coef >= 0, "ent_coef", "at least 0", c.ent_coef);
  check(c.vf_coef >= 0, "vf_coef", "at least 0", c.vf_coef);
  check(c.max_grad_norm > 0, "max_grad_norm", "positive", c.max_grad_norm);
  check(!c.target_kl.has_value() || *c.target_kl > 0, "target_kl", "positive",
        c.target_kl.value_or(0));
  check(c.adam_eps > 0, "adam_eps", "positive", c.adam_eps);
  check(c.cnn_features >= 1, "cnn_features", "at least 1", c.cnn_features);
  for (const auto& [name, layers] : {std::pair{"pi_layers", &c.pi_layers},
                                     std::pair{"vf_layers", &c.vf_layers},
                                     std::pair{"context_layers", &c.context_layers}}) {
    for (int width : *layers) check(width >= 1, name, "a list of positive widths", width);
  }
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
