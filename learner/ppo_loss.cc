// Copyright 2026 The DCS Authors.
#include "learner/ppo_loss.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "absl/container/inlined_vector.h"

namespace dcs::learner {
namespace {

const float kHalfLog2Pi = static_cast<float>(0.5 * std::log(2 * std::numbers::pi));

// One sample's distribution over actions, given the action head's output. Made for every
// sample of every minibatch: its log-probabilities stay off the heap for up to 16 actions.
class Categorical {
 public:
  // torch's log_softmax: (x - max) - log(sum(exp(x - max))).
  explicit Categorical(std::span<const float> logits) : log_p_(logits.size()) {
    const float max = *std::max_element(logits.begin(), logits.end());
    float sum = 0;
    for (float x : logits) sum += std::exp(x - max);
    const float log_sum = std::log(sum);
    for (size_t j = 0; j < logits.size(); ++j) log_p_[j] = (logits[j] - max) - log_sum;
  }

  float LogProb(float action) const { return log_p_[static_cast<size_t>(action)]; }

  float Entropy() const {
    float entropy = 0;
    for (float log_p : log_p_) entropy -= std::exp(log_p) * log_p;
    return entropy;
  }

  // d/d logits of (d_log_prob * log p(action) + d_entropy * H).
  void Gradient(float action, float d_log_prob, float d_entropy, std::span<float> d_logits) const {
    const float entropy = d_entropy != 0 ? Entropy() : 0;
    for (size_t j = 0; j < log_p_.size(); ++j) {
      const float p = std::exp(log_p_[j]);
      const float indicator = j == static_cast<size_t>(action) ? 1.0f : 0.0f;
      d_logits[j] = d_log_prob * (indicator - p) - d_entropy * p * (log_p_[j] + entropy);
    }
  }

 private:
  absl::InlinedVector<float, 16> log_p_;
};

// A diagonal Gaussian N(mean, exp(log_std)^2): z = (action - mean) / std,
// log p = sum(-z^2 / 2 - log_std - log(2 pi) / 2), H = sum(1/2 + log(2 pi) / 2 + log_std).
struct Gaussian {
  std::span<const float> mean;
  std::span<const float> log_std;

  float Z(std::span<const float> action, size_t j) const {
    return (action[j] - mean[j]) * std::exp(-log_std[j]);
  }

  float LogProb(std::span<const float> action) const {
    float log_prob = 0;
    for (size_t j = 0; j < mean.size(); ++j) {
      const float z = Z(action, j);
      log_prob += -0.5f * z * z - log_std[j] - kHalfLog2Pi;
    }
    return log_prob;
  }

  float Entropy() const {
    float entropy = 0;
    for (float s : log_std) entropy += 0.5f + kHalfLog2Pi + s;
    return entropy;
  }

  // d/d mean of d_log_prob * log p(action); adds d/d log_std of it to `d_log_std`.
  void Gradient(std::span<const float> action, float d_log_prob, std::span<float> d_mean,
                std::span<float> d_log_std) const {
    for (size_t j = 0; j < mean.size(); ++j) {
      const float z = Z(action, j);
      d_mean[j] = d_log_prob * z * std::exp(-log_std[j]);
      d_log_std[j] += d_log_prob * (z * z - 1);
    }
  }
};

}  // namespace

void ActionLogProbs(const run::PolicySpec& spec, std::span<const float> head,
                    std::span<const float> log_std, std::span<const float> actions,
                    std::span<float> log_probs) {
  const size_t a = spec.head_size();
  for (size_t i = 0; i < log_probs.size(); ++i) {
    const std::span<const float> row = head.subspan(i * a, a);
    log_probs[i] = spec.discrete()
                       ? Categorical(row).LogProb(actions[i])
                       : Gaussian{row, log_std}.LogProb(actions.subspan(i * a, a));
  }
}

PpoLoss ComputePpoLoss(const run::PolicySpec& spec, const run::PpoConfig& config,
                       const PpoLossInput& input, const PpoLossGradient& gradient) {
  const int b = input.size;
  const size_t a = spec.head_size();
  const auto clip = static_cast<float>(config.clip_range);
  const auto ent_coef = static_cast<float>(config.ent_coef);
  const auto vf_coef = static_cast<float>(config.vf_coef);
  std::fill(gradient.log_std.begin(), gradient.log_std.end(), 0.0f);
  PpoLoss loss;
  int clipped = 0;
  for (int i = 0; i < b; ++i) {
    const std::span<const float> head = input.head.subspan(i * a, a);
    const std::span<float> d_head = gradient.head.subspan(i * a, a);
    const std::optional<Categorical> categorical =
        spec.discrete() ? std::optional<Categorical>(head) : std::nullopt;
    const Gaussian gaussian{head, input.log_std};
    const std::span<const float> action = input.actions.subspan(i * spec.action_size,
                                                                spec.action_size);
    const float log_prob =
        categorical ? categorical->LogProb(action[0]) : gaussian.LogProb(action);
    const float entropy = categorical ? categorical->Entropy() : gaussian.Entropy();

    const float ratio = std::exp(log_prob - input.old_log_probs[i]);
    const float advantage = input.advantages[i];
    const float unclipped = advantage * ratio;
    const float clipped_surrogate = advantage * std::clamp(ratio, 1 - clip, 1 + clip);
    loss.policy -= std::min(unclipped, clipped_surrogate);
    loss.approx_kl += (ratio - 1.0) - std::log(static_cast<double>(ratio));
    clipped += std::abs(ratio - 1.0f) > clip;
    loss.entropy -= entropy;
    // d loss / d log_prob: through the unclipped term when it is the smaller; the clipped
    // term's is zero whenever it is strictly the smaller (the ratio is then outside the clip).
    const float d_log_prob =
        unclipped <= clipped_surrogate ? -advantage * ratio / static_cast<float>(b) : 0.0f;
    const float d_entropy = -ent_coef / static_cast<float>(b);  // d loss / d H
    if (categorical) {
      categorical->Gradient(action[0], d_log_prob, d_entropy, d_head);
    } else {
      gaussian.Gradient(action, d_log_prob, d_head, gradient.log_std);
    }

    const float value = input.values[i];
    float predicted = value;
    bool value_passes = true;
    if (config.clip_range_vf.has_value()) {
      const auto clip_vf = static_cast<float>(*config.clip_range_vf);
      const float change = value - input.old_values[i];
      predicted = input.old_values[i] + std::clamp(change, -clip_vf, clip_vf);
      value_passes = change >= -clip_vf && change <= clip_vf;
    }
    const float error = predicted - input.returns[i];
    loss.value += static_cast<double>(error) * error;
    gradient.values[i] =
        value_passes ? vf_coef * 2.0f * error / static_cast<float>(b) : 0.0f;
  }
  if (!spec.discrete()) {
    // H = sum(... + log_std) for every sample: d (ent_coef * -mean(H)) / d log_std = -ent_coef.
    for (float& d : gradient.log_std) d -= ent_coef;
  }
  loss.policy /= b;
  loss.value /= b;
  loss.entropy /= b;
  loss.approx_kl /= b;
  loss.clip_fraction = static_cast<double>(clipped) / b;
  loss.total = loss.policy + config.vf_coef * loss.value + config.ent_coef * loss.entropy;
  return loss;
}

}  // namespace dcs::learner
