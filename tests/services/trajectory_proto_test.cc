// Copyright 2026 The DCS Authors.
#include "services/trajectory_proto.h"

#include <limits>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

using ::testing::HasSubstr;

actor::SlotRollout TwoSteps() {
  return {.slot = 2,
          .num_steps = 2,
          .inputs = {1, 2, 3, 4, 5, 6},
          .actions = {1, 0},
          .rewards = {1.5, -2.5},
          .episode_starts = {1, 0},
          .truncations = {{.step = 1, .input = {7, 8, 9}}},
          .last_input = {10, 11, 12},
          .last_done = true,
          .finished = {{.episode_return = 4, .length = 9, .step = 1}},
          .journal = {.episode = 3, .reset_step = 96, .actions = {0, 1, 1}, .episode_return = 2}};
}

TEST(TrajectoryProtoTest, ASlotsRolloutRoundTripsAsTensorsOfItsShape) {
  const v1::SlotRollout proto = SlotRolloutToProto(TwoSteps());
  EXPECT_THAT(proto.inputs().shape(), testing::ElementsAre(2, 3));
  EXPECT_EQ(proto.inputs().dtype(), v1::D_TYPE_FLOAT32);
  EXPECT_EQ(proto.episode_starts().dtype(), v1::D_TYPE_UINT8);
  absl::StatusOr<actor::SlotRollout> back = SlotRolloutFromProto(proto);
  ASSERT_TRUE(back.ok()) << back.status();
  const actor::SlotRollout expected = TwoSteps();
  EXPECT_EQ(back->slot, 2);
  EXPECT_EQ(back->inputs, expected.inputs);
  EXPECT_EQ(back->actions, expected.actions);
  EXPECT_EQ(back->rewards, expected.rewards);
  EXPECT_EQ(back->episode_starts, expected.episode_starts);
  ASSERT_EQ(back->truncations.size(), 1u);
  EXPECT_EQ(back->truncations[0].input, expected.truncations[0].input);
  EXPECT_EQ(back->last_input, expected.last_input);
  EXPECT_TRUE(back->last_done);
  ASSERT_EQ(back->finished.size(), 1u);
  EXPECT_EQ(back->finished[0].length, 9);
  EXPECT_EQ(back->journal.actions, expected.journal.actions);
  EXPECT_EQ(back->journal.reset_step, 96);
}

TEST(TrajectoryProtoTest, RefusesATensorWhoseShapeIsNotItsLength) {
  v1::SlotRollout proto = SlotRolloutToProto(TwoSteps());
  proto.mutable_inputs()->set_shape(1, 4);
  EXPECT_THAT(SlotRolloutFromProto(proto).status().message(),
              HasSubstr("inputs: shape [2, 4] of D_TYPE_FLOAT32 needs 32 bytes, the data has 24"));
}

TEST(TrajectoryProtoTest, RefusesHugeOrNegativeShapesWithoutAllocating) {
  v1::SlotRollout proto = SlotRolloutToProto(TwoSteps());
  proto.mutable_rewards()->set_shape(0, std::numeric_limits<int64_t>::max() / 2);
  EXPECT_THAT(SlotRolloutFromProto(proto).status().message(), HasSubstr("is not a valid shape"));
  proto = SlotRolloutToProto(TwoSteps());
  proto.mutable_rewards()->set_shape(0, -2);
  EXPECT_EQ(SlotRolloutFromProto(proto).status().code(), absl::StatusCode::kInvalidArgument);
}

// Issue 14 (found by tests/fuzz/data_plane_fuzzer): a tensor with a dimension of 0 and no data
// copied its 0 bytes to an empty vector's null data(), which is undefined (UBSan: null pointer
// passed to memcpy; the sanitizer job runs this test). It is an empty array.
TEST(TrajectoryProtoTest, ATensorWithADimensionOfZeroIsEmpty) {
  v1::SlotJournal proto = JournalToProto(TwoSteps().journal);
  proto.mutable_actions()->clear_shape();
  proto.mutable_actions()->add_shape(0);
  proto.mutable_actions()->add_shape(1);
  proto.mutable_actions()->clear_data();
  const absl::StatusOr<actor::SlotJournal> journal = JournalFromProto(proto);
  ASSERT_TRUE(journal.ok()) << journal.status();
  EXPECT_TRUE(journal->actions.empty());
}

TEST(TrajectoryProtoTest, RefusesTheWrongDtype) {
  v1::SlotRollout proto = SlotRolloutToProto(TwoSteps());
  proto.mutable_rewards()->set_dtype(v1::D_TYPE_UINT8);
  EXPECT_THAT(SlotRolloutFromProto(proto).status().message(),
              HasSubstr("rewards: dtype D_TYPE_UINT8, expected D_TYPE_FLOAT32"));
}

TEST(TrajectoryProtoTest, PolicyWeightsRoundTrip) {
  const actor::PolicyWeights weights{
      .layers = {{.inputs = 2, .outputs = 3, .weight = {1, 2, 3, 4, 5, 6}, .bias = {7, 8, 9}},
                 {.inputs = 3,
                  .outputs = 1,
                  .weight = {1, 1, 1},
                  .bias = {0},
                  .activation = actor::Activation::kNone}},
      .log_std = {-0.5},
      .num_actions = 0};
  absl::StatusOr<actor::PolicyWeights> back = WeightsFromProto(WeightsToProto(weights));
  ASSERT_TRUE(back.ok()) << back.status();
  ASSERT_EQ(back->layers.size(), 2u);
  EXPECT_EQ(back->layers[0].inputs, 2);
  EXPECT_EQ(back->layers[0].outputs, 3);
  EXPECT_EQ(back->layers[0].weight, weights.layers[0].weight);
  EXPECT_EQ(back->layers[1].activation, actor::Activation::kNone);
  EXPECT_EQ(back->log_std, weights.log_std);
  EXPECT_FALSE(back->image.has_value());
}

TEST(TrajectoryProtoTest, ImagePolicyWeightsRoundTrip) {
  const actor::PolicyWeights weights{
      .image = actor::ImageEncoderWeights{.height = 3,
                                          .width = 3,
                                          .channels = 2,
                                          .convs = {{.in_channels = 2,
                                                     .out_channels = 1,
                                                     .kernel = 2,
                                                     .stride = 1,
                                                     .weight = {1, 2, 3, 4, 5, 6, 7, 8},
                                                     .bias = {0.5f}}},
                                          .linear = {.inputs = 4,
                                                     .outputs = 1,
                                                     .weight = {1, 2, 3, 4},
                                                     .bias = {0},
                                                     .activation = actor::Activation::kRelu}},
      .context_layers = {{.inputs = 3,
                          .outputs = 1,
                          .weight = {1, 2, 3},
                          .bias = {4},
                          .activation = actor::Activation::kRelu}},
      .layers = {{.inputs = 2,
                  .outputs = 2,
                  .weight = {1, 0, 0, 1},
                  .bias = {0, 0},
                  .activation = actor::Activation::kNone}},
      .num_actions = 2};
  absl::StatusOr<actor::PolicyWeights> back = WeightsFromProto(WeightsToProto(weights));
  ASSERT_TRUE(back.ok()) << back.status();
  ASSERT_TRUE(back->image.has_value());
  EXPECT_EQ(back->image->height, 3);
  EXPECT_EQ(back->image->channels, 2);
  ASSERT_EQ(back->image->convs.size(), 1u);
  EXPECT_EQ(back->image->convs[0].in_channels, 2);
  EXPECT_EQ(back->image->convs[0].kernel, 2);
  EXPECT_EQ(back->image->convs[0].weight, weights.image->convs[0].weight);
  EXPECT_EQ(back->image->linear.activation, actor::Activation::kRelu);
  ASSERT_EQ(back->context_layers.size(), 1u);
  EXPECT_EQ(back->context_layers[0].inputs, 3);
  EXPECT_EQ(back->context_layers[0].weight, weights.context_layers[0].weight);
  EXPECT_EQ(back->context_layers[0].activation, actor::Activation::kRelu);
  EXPECT_EQ(back->image->linear.weight, weights.image->linear.weight);

  v1::PolicyWeights unknown = WeightsToProto(weights);
  unknown.mutable_layers(0)->set_activation(v1::ACTIVATION_UNSPECIFIED);
  EXPECT_THAT(WeightsFromProto(unknown).status().message(),
              HasSubstr("layers.activation: 0 is not an activation"));
}

}  // namespace
}  // namespace dcs::services
