// Copyright 2026 The DCS Authors.
//
// PolicyNetwork (actor/policy_network.h) on batches: a sample's outputs and actions are the same
// bits whatever else shares its batch, for layer widths that fill Eigen's packets and widths
// that do not; and a batch's deterministic actions are its samples' modes.

#include "actor/policy_network.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "common/random.h"
#include "gtest/gtest.h"

namespace dcs::actor {
namespace {

DenseLayer RandomLayer(int inputs, int outputs, Activation activation, Random& random) {
  DenseLayer layer{.inputs = inputs, .outputs = outputs, .activation = activation};
  for (int i = 0; i < inputs * outputs; ++i) {
    layer.weight.push_back(static_cast<float>(random.Normal(0, 1.0 / std::sqrt(inputs))));
  }
  for (int i = 0; i < outputs; ++i) layer.bias.push_back(static_cast<float>(random.Normal(0, 0.1)));
  return layer;
}

// An MLP policy: `widths` tanh layers on `inputs` floats, then a head of `head` outputs (a
// categorical policy's logits, or a Gaussian's means when `gaussian`).
PolicyNetwork RandomPolicy(int inputs, const std::vector<int>& widths, int head, bool gaussian) {
  Random random(17);
  PolicyWeights weights;
  int from = inputs;
  for (int width : widths) {
    weights.layers.push_back(RandomLayer(from, width, Activation::kTanh, random));
    from = width;
  }
  weights.layers.push_back(RandomLayer(from, head, Activation::kNone, random));
  if (gaussian) {
    weights.log_std.assign(head, -0.5f);
  } else {
    weights.num_actions = head;
  }
  absl::StatusOr<PolicyNetwork> policy = PolicyNetwork::Create(weights);
  EXPECT_TRUE(policy.ok()) << policy.status();
  return *std::move(policy);
}

std::vector<float> RandomInputs(int count, int size, uint64_t seed) {
  Random random(seed);
  std::vector<float> inputs(static_cast<size_t>(count) * size);
  for (float& x : inputs) x = static_cast<float>(random.Uniform(-2, 2));
  return inputs;
}

// Every sample of batches of 1 to 40 has the head outputs it has alone, bit for bit.
void ExpectSamplesIndependentOfTheirBatch(PolicyNetwork& policy) {
  const int in = policy.input_size();
  const int head = policy.head_size();
  constexpr int kLargest = 40;
  const std::vector<float> inputs = RandomInputs(kLargest, in, 5);
  std::vector<float> alone(static_cast<size_t>(kLargest) * head);
  for (int i = 0; i < kLargest; ++i) {
    policy.Forward(1, std::span<const float>(inputs).subspan(i * in, in), {},
                   std::span<float>(alone).subspan(i * head, head));
  }
  for (int count = 1; count <= kLargest; ++count) {
    // The last `count` samples, so that each sample takes every position of some batch.
    const int first = kLargest - count;
    std::vector<float> together(static_cast<size_t>(count) * head);
    policy.Forward(count, std::span<const float>(inputs).subspan(first * in, count * in), {},
                   together);
    for (int i = 0; i < count; ++i) {
      for (int j = 0; j < head; ++j) {
        // Bits, not values: the same float compares equal to itself only if not NaN.
        EXPECT_EQ(std::bit_cast<uint32_t>(together[i * head + j]),
                  std::bit_cast<uint32_t>(alone[(first + i) * head + j]))
            << "sample " << first + i << ", output " << j << ", in a batch of " << count;
      }
    }
  }
}

TEST(PolicyNetworkTest, ASamplesOutputsDoNotDependOnItsBatchWithCartPolesShape) {
  PolicyNetwork policy = RandomPolicy(5, {64, 64}, 2, /*gaussian=*/false);
  ExpectSamplesIndependentOfTheirBatch(policy);
}

TEST(PolicyNetworkTest, ASamplesOutputsDoNotDependOnItsBatchWithPartFilledPackets) {
  // Widths that are no multiple of Eigen's 8 floats: the network pads them.
  PolicyNetwork policy = RandomPolicy(27, {13, 100}, 3, /*gaussian=*/true);
  ExpectSamplesIndependentOfTheirBatch(policy);
}

TEST(PolicyNetworkTest, ABatchActsAsItsSamplesAlone) {
  PolicyNetwork policy = RandomPolicy(24, {64, 64}, 4, /*gaussian=*/true);
  constexpr int kCount = 9;
  const std::vector<float> inputs = RandomInputs(kCount, 24, 8);
  std::vector<Random> randoms;
  for (int i = 0; i < kCount; ++i) randoms.emplace_back(100 + i);
  std::vector<float> actions(kCount * 4);
  policy.Act(kCount, inputs, {}, /*deterministic=*/false, randoms, actions);
  std::vector<float> modes(kCount * 4);
  policy.Act(kCount, inputs, {}, /*deterministic=*/true, {}, modes);
  std::vector<float> means(kCount * 4);
  policy.Forward(kCount, inputs, {}, means);
  EXPECT_EQ(modes, means);  // a Gaussian's mode is its mean
  for (int i = 0; i < kCount; ++i) {
    Random random(100 + i);
    std::vector<float> action(4);
    policy.Act(1, std::span<const float>(inputs).subspan(i * 24, 24), {}, false, {&random, 1},
               action);
    EXPECT_EQ(action, std::vector<float>(actions.begin() + i * 4, actions.begin() + i * 4 + 4))
        << "sample " << i;
    EXPECT_NE(action, std::vector<float>(modes.begin() + i * 4, modes.begin() + i * 4 + 4));
  }
}

TEST(PolicyNetworkTest, DeterministicCategoricalActionsAreTheArgmax) {
  PolicyNetwork policy = RandomPolicy(5, {64, 64}, 3, /*gaussian=*/false);
  constexpr int kCount = 50;
  const std::vector<float> inputs = RandomInputs(kCount, 5, 9);
  std::vector<float> logits(kCount * 3);
  policy.Forward(kCount, inputs, {}, logits);
  std::vector<float> actions(kCount);
  policy.Act(kCount, inputs, {}, /*deterministic=*/true, {}, actions);
  for (int i = 0; i < kCount; ++i) {
    const auto row = std::span<const float>(logits).subspan(i * 3, 3);
    EXPECT_EQ(actions[i], static_cast<float>(std::max_element(row.begin(), row.end()) - row.begin()));
  }
}

}  // namespace
}  // namespace dcs::actor
