// Copyright 2026 The DCS Authors.
#include "services/trajectory_proto.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"

namespace dcs::services {
namespace {

template <typename T>
constexpr v1::DType kDType = std::is_same_v<T, float> ? v1::D_TYPE_FLOAT32 : v1::D_TYPE_UINT8;

// A tensor of `values` in rows of `row_size` (a vector if row_size is 0).
template <typename T>
v1::Tensor ToTensor(std::span<const T> values, int64_t row_size = 0) {
  v1::Tensor tensor;
  tensor.set_dtype(kDType<T>);
  if (row_size > 0) {
    tensor.add_shape(static_cast<int64_t>(values.size()) / row_size);
    tensor.add_shape(row_size);
  } else {
    tensor.add_shape(static_cast<int64_t>(values.size()));
  }
  tensor.set_data(values.data(), values.size() * sizeof(T));
  return tensor;
}

template <typename T>
v1::Tensor ToTensor(const std::vector<T>& values, int64_t row_size = 0) {
  return ToTensor(std::span<const T>(values), row_size);
}

// The elements of `tensor`, checked: its dtype is T's, and its shape's product times T's size
// is its byte length. An empty tensor (no shape, no data) is an empty array.
template <typename T>
absl::StatusOr<std::vector<T>> FromTensor(const v1::Tensor& tensor, absl::string_view field) {
  if (tensor.shape_size() == 0 && tensor.data().empty()) return std::vector<T>();
  if (tensor.dtype() != kDType<T>) {
    return absl::InvalidArgumentError(absl::StrCat(field, ": dtype ",
                                                   v1::DType_Name(tensor.dtype()), ", expected ",
                                                   v1::DType_Name(kDType<T>)));
  }
  int64_t elements = 1;
  for (int64_t dimension : tensor.shape()) {
    if (dimension < 0 || (dimension > 0 && elements > std::numeric_limits<int64_t>::max() /
                                                          static_cast<int64_t>(sizeof(T)) /
                                                          dimension)) {
      return absl::InvalidArgumentError(absl::StrCat(
          field, ": shape [", absl::StrJoin(tensor.shape(), ", "), "] is not a valid shape"));
    }
    elements *= dimension;
  }
  if (static_cast<uint64_t>(elements) * sizeof(T) != tensor.data().size()) {
    return absl::InvalidArgumentError(absl::StrCat(
        field, ": shape [", absl::StrJoin(tensor.shape(), ", "), "] of ", v1::DType_Name(kDType<T>),
        " needs ", elements * static_cast<int64_t>(sizeof(T)), " bytes, the data has ",
        tensor.data().size()));
  }
  std::vector<T> values(static_cast<size_t>(elements));
  std::memcpy(values.data(), tensor.data().data(), tensor.data().size());
  return values;
}

}  // namespace

v1::SlotJournal JournalToProto(const actor::SlotJournal& journal) {
  v1::SlotJournal proto;
  proto.set_episode(journal.episode);
  proto.set_reset_step(journal.reset_step);
  *proto.mutable_actions() = ToTensor(journal.actions);
  proto.set_episode_return(journal.episode_return);
  return proto;
}

absl::StatusOr<actor::SlotJournal> JournalFromProto(const v1::SlotJournal& proto) {
  DCS_ASSIGN_OR_RETURN(std::vector<float> actions,
                       FromTensor<float>(proto.actions(), "journal.actions"));
  return actor::SlotJournal{.episode = proto.episode(),
                            .reset_step = proto.reset_step(),
                            .actions = std::move(actions),
                            .episode_return = proto.episode_return()};
}

v1::SlotRollout SlotRolloutToProto(const actor::SlotRollout& rollout) {
  v1::SlotRollout proto;
  const int64_t steps = std::max(rollout.num_steps, 1);
  proto.set_slot(rollout.slot);
  proto.set_num_steps(rollout.num_steps);
  *proto.mutable_inputs() = ToTensor(rollout.inputs, rollout.inputs.size() / steps);
  if (!rollout.images.empty()) {
    *proto.mutable_images() = ToTensor(rollout.images, rollout.images.size() / steps);
  }
  *proto.mutable_actions() = ToTensor(rollout.actions, rollout.actions.size() / steps);
  *proto.mutable_rewards() = ToTensor(rollout.rewards);
  *proto.mutable_episode_starts() = ToTensor(rollout.episode_starts);
  for (const actor::Rollout::Truncation& cut : rollout.truncations) {
    v1::Truncation& truncation = *proto.add_truncations();
    truncation.set_step(cut.step);
    *truncation.mutable_input() = ToTensor(cut.input);
    if (!cut.image.empty()) *truncation.mutable_image() = ToTensor(cut.image);
  }
  *proto.mutable_last_input() = ToTensor(rollout.last_input);
  if (!rollout.last_image.empty()) *proto.mutable_last_image() = ToTensor(rollout.last_image);
  proto.set_last_done(rollout.last_done);
  for (const actor::EpisodeSummary& episode : rollout.finished) {
    v1::FinishedEpisode& finished = *proto.add_finished();
    finished.set_episode_return(episode.episode_return);
    finished.set_length(episode.length);
    finished.set_step(episode.step);
  }
  *proto.mutable_journal() = JournalToProto(rollout.journal);
  return proto;
}

absl::StatusOr<actor::SlotRollout> SlotRolloutFromProto(const v1::SlotRollout& proto) {
  actor::SlotRollout rollout{.slot = proto.slot(), .num_steps = proto.num_steps()};
  DCS_ASSIGN_OR_RETURN(rollout.inputs, FromTensor<float>(proto.inputs(), "inputs"));
  DCS_ASSIGN_OR_RETURN(rollout.images, FromTensor<uint8_t>(proto.images(), "images"));
  DCS_ASSIGN_OR_RETURN(rollout.actions, FromTensor<float>(proto.actions(), "actions"));
  DCS_ASSIGN_OR_RETURN(rollout.rewards, FromTensor<float>(proto.rewards(), "rewards"));
  DCS_ASSIGN_OR_RETURN(rollout.episode_starts,
                       FromTensor<uint8_t>(proto.episode_starts(), "episode_starts"));
  for (const v1::Truncation& truncation : proto.truncations()) {
    actor::Rollout::Truncation cut{.step = truncation.step()};
    DCS_ASSIGN_OR_RETURN(cut.input, FromTensor<float>(truncation.input(), "truncations.input"));
    DCS_ASSIGN_OR_RETURN(cut.image, FromTensor<uint8_t>(truncation.image(), "truncations.image"));
    rollout.truncations.push_back(std::move(cut));
  }
  DCS_ASSIGN_OR_RETURN(rollout.last_input, FromTensor<float>(proto.last_input(), "last_input"));
  DCS_ASSIGN_OR_RETURN(rollout.last_image, FromTensor<uint8_t>(proto.last_image(), "last_image"));
  rollout.last_done = proto.last_done();
  for (const v1::FinishedEpisode& episode : proto.finished()) {
    rollout.finished.push_back(
        {.episode_return = episode.episode_return(), .length = episode.length(),
         .step = episode.step()});
  }
  DCS_ASSIGN_OR_RETURN(rollout.journal, JournalFromProto(proto.journal()));
  return rollout;
}

v1::PolicyWeights WeightsToProto(const actor::MlpWeights& weights) {
  v1::PolicyWeights proto;
  for (const actor::DenseLayer& layer : weights.layers) {
    v1::DenseLayer& out = *proto.add_layers();
    *out.mutable_weight() = ToTensor(layer.weight, layer.inputs);
    *out.mutable_bias() = ToTensor(layer.bias);
    out.set_tanh(layer.tanh);
  }
  *proto.mutable_log_std() = ToTensor(weights.log_std);
  proto.set_num_actions(weights.num_actions);
  return proto;
}

absl::StatusOr<actor::MlpWeights> WeightsFromProto(const v1::PolicyWeights& proto) {
  actor::MlpWeights weights{.num_actions = proto.num_actions()};
  for (const v1::DenseLayer& in : proto.layers()) {
    if (in.weight().shape_size() != 2) {
      return absl::InvalidArgumentError("a layer's weight must have shape [outputs, inputs]");
    }
    actor::DenseLayer layer{.inputs = static_cast<int>(in.weight().shape(1)),
                            .outputs = static_cast<int>(in.weight().shape(0)),
                            .tanh = in.tanh()};
    DCS_ASSIGN_OR_RETURN(layer.weight, FromTensor<float>(in.weight(), "layers.weight"));
    DCS_ASSIGN_OR_RETURN(layer.bias, FromTensor<float>(in.bias(), "layers.bias"));
    weights.layers.push_back(std::move(layer));
  }
  DCS_ASSIGN_OR_RETURN(weights.log_std, FromTensor<float>(proto.log_std(), "log_std"));
  return weights;
}

}  // namespace dcs::services
