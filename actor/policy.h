// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_POLICY_H_
#define DCS_ACTOR_POLICY_H_

// What acts in environments: given a batch of the policy's inputs (each the flat observation
// and context, and an image for image policies) it samples an action per sample from its
// distribution, or takes the mode. Actions are unclipped; whoever steps an environment clips
// continuous actions to its bounds. A sample's action depends on its own input (and random
// source) alone, whatever else shares its batch, so slots and episodes may be batched however
// the caller likes. Implementation: actor::PolicyNetwork (Eigen), for vector and image
// observations alike. Confined to one thread.

#include <cstdint>
#include <span>

#include "common/random.h"

namespace dcs::actor {

// An action from a policy head's output: for a categorical policy (num_actions > 0) `head` holds
// logits and the action is a sampled index (the argmax without `random`); for a diagonal
// Gaussian it holds the mean, and the action is mean + std * N(0, 1) (the mean without
// `random`), unclipped. REQUIRES: action has 1 (categorical) or head.size() elements.
void SampleAction(std::span<const float> head, std::span<const float> std, int num_actions,
                  Random* random, std::span<float> action);

class Policy {
 public:
  virtual ~Policy() = default;

  // The actions of `count` samples: sample i's input is the i-th run of the policy's flat input
  // size in `inputs` and the i-th image in `images` (empty for a policy without image); its
  // action goes to the i-th run of the action size in `actions`, drawn with randoms[i], or the
  // mode when `deterministic` (then `randoms` may be empty).
  // REQUIRES: the spans hold `count` samples each (randoms too, unless deterministic).
  virtual void Act(int count, std::span<const float> inputs, std::span<const uint8_t> images,
                   bool deterministic, std::span<Random> randoms, std::span<float> actions) = 0;
};

}  // namespace dcs::actor

#endif  // DCS_ACTOR_POLICY_H_
