// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_POLICY_H_
#define DCS_ACTOR_POLICY_H_

// What acts in an environment: given the policy's input (the flat observation and context, and
// an image for image policies) it samples an action from its distribution, or takes the mode.
// Actions are unclipped; whoever steps the environment clips continuous actions to its bounds.
// Implementation: actor::PolicyNetwork (Eigen), for vector and image observations alike.
// Confined to one thread.

#include <cstdint>
#include <span>

#include "common/random.h"

namespace dcs::actor {

// An action from a policy head's output: for a categorical policy (num_actions > 0) `head` holds
// logits and the action is a sampled index (the argmax when deterministic); for a diagonal
// Gaussian it holds the mean, and the action is mean + std * N(0, 1) (the mean when
// deterministic), unclipped. REQUIRES: action has 1 (categorical) or head.size() elements.
void SampleAction(std::span<const float> head, std::span<const float> std, int num_actions,
                  bool deterministic, Random& random, std::span<float> action);

class Policy {
 public:
  virtual ~Policy() = default;

  // REQUIRES: `inputs` has the policy's flat input size, `image` its image bytes (or is empty
  // for a policy without image), `action` its action size.
  virtual void Act(std::span<const float> inputs, std::span<const uint8_t> image,
                   bool deterministic, Random& random, std::span<float> action) = 0;
};

}  // namespace dcs::actor

#endif  // DCS_ACTOR_POLICY_H_
