// Copyright 2026 The DCS Authors.
#include "learner/ppo_config.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace dcs::learner {
namespace {

absl::Status Field(bool ok, absl::string_view name, absl::string_view rule, double value) {
  if (ok) return absl::OkStatus();
  return absl::InvalidArgumentError(
      absl::StrCat("ppo: ", name, " must be ", rule, ", got ", value));
}

}  // namespace

absl::Status ValidatePpoConfig(const PpoConfig& c, int n_envs) {
  for (const absl::Status& status : {
           Field(c.learning_rate > 0 && std::isfinite(c.learning_rate), "learning_rate",
                 "positive", c.learning_rate),
           Field(c.n_steps >= 1, "n_steps", "at least 1", c.n_steps),
           Field(c.batch_size >= 1, "batch_size", "at least 1", c.batch_size),
           Field(!c.normalize_advantage || c.batch_size > 1, "batch_size",
                 "greater than 1 when advantages are normalised", c.batch_size),
           Field(static_cast<int64_t>(c.n_steps) * n_envs > 1, "n_steps * n_envs",
                 "greater than 1", static_cast<double>(c.n_steps) * n_envs),
           Field(c.n_epochs >= 1, "n_epochs", "at least 1", c.n_epochs),
           Field(c.gamma >= 0 && c.gamma <= 1, "gamma", "in [0, 1]", c.gamma),
           Field(c.gae_lambda >= 0 && c.gae_lambda <= 1, "gae_lambda", "in [0, 1]",
                 c.gae_lambda),
           Field(c.clip_range > 0, "clip_range", "positive", c.clip_range),
           Field(!c.clip_range_vf.has_value() || *c.clip_range_vf > 0, "clip_range_vf",
                 "positive", c.clip_range_vf.value_or(0)),
           Field(c.ent_coef >= 0, "ent_coef", "at least 0", c.ent_coef),
           Field(c.vf_coef >= 0, "vf_coef", "at least 0", c.vf_coef),
           Field(c.max_grad_norm > 0, "max_grad_norm", "positive", c.max_grad_norm),
           Field(!c.target_kl.has_value() || *c.target_kl > 0, "target_kl", "positive",
                 c.target_kl.value_or(0)),
           Field(c.adam_eps > 0, "adam_eps", "positive", c.adam_eps),
           Field(c.cnn_features >= 1, "cnn_features", "at least 1", c.cnn_features),
       }) {
    if (!status.ok()) return status;
  }
  for (const auto& [name, layers] : {std::pair{"pi_layers", &c.pi_layers},
                                     std::pair{"vf_layers", &c.vf_layers}}) {
    for (int width : *layers) {
      if (width < 1) return Field(false, name, "a list of positive widths", width);
    }
  }
  return absl::OkStatus();
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

}  // namespace dcs::learner
