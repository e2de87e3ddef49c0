// Copyright 2026 The DCS Authors.
#include "services/trajectory_proto.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
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

// A tensor of `values` with `shape`. REQUIRES: the shape's product is values.size().
v1::Tensor ToTensor(const std::vector<float>& values, std::initializer_list<int64_t> shape) {
  v1::Tensor tensor = ToTensor(values);
  tensor.clear_shape();
  for (int64_t dimension : shape) tensor.add_shape(dimension);
  return tensor;
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
  // Not for no elements (a dimension of 0): memcpy to an empty vector's null data() is undefined
  // even for 0 bytes.
  if (!values.empty()) std::memcpy(values.data(), tensor.data().data(), tensor.data().size());
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

namespace {

// The one table of activations on the wire.
constexpr std::pair<actor::Activation, v1::Activation> kActivations[] = {
    {actor::Activation::kNone, v1::ACTIVATION_NONE},
    {actor::Activation::kTanh, v1::ACTIVATION_TANH},
    {actor::Activation::kRelu, v1::ACTIVATION_RELU},
};

v1::DenseLayer DenseToProto(const actor::DenseLayer& layer) {
  v1::DenseLayer proto;
  *proto.mutable_weight() = ToTensor(layer.weight, layer.inputs);
  *proto.mutable_bias() = ToTensor(layer.bias);
  for (const auto& [activation, wire] : kActivations) {
    if (activation == layer.activation) proto.set_activation(wire);
  }
  return proto;
}

absl::StatusOr<actor::DenseLayer> DenseFromProto(const v1::DenseLayer& proto,
                                                 absl::string_view field) {
  if (proto.weight().shape_size() != 2) {
    return absl::InvalidArgumentError(
        absl::StrCat(field, ".weight must have shape [outputs, inputs]"));
  }
  actor::DenseLayer layer{.inputs = static_cast<int>(proto.weight().shape(1)),
                          .outputs = static_cast<int>(proto.weight().shape(0))};
  DCS_ASSIGN_OR_RETURN(layer.weight,
                       FromTensor<float>(proto.weight(), absl::StrCat(field, ".weight")));
  DCS_ASSIGN_OR_RETURN(layer.bias, FromTensor<float>(proto.bias(), absl::StrCat(field, ".bias")));
  const auto* known =
      std::find_if(std::begin(kActivations), std::end(kActivations),
                   [&](const auto& entry) { return entry.second == proto.activation(); });
  if (known == std::end(kActivations)) {
    return absl::InvalidArgumentError(
        absl::StrCat(field, ".activation: ", proto.activation(), " is not an activation"));
  }
  layer.activation = known->first;
  return layer;
}

absl::Status DenseLayersFromProto(const google::protobuf::RepeatedPtrField<v1::DenseLayer>& protos,
                                  absl::string_view field, std::vector<actor::DenseLayer>& layers) {
  for (const v1::DenseLayer& proto : protos) {
    DCS_ASSIGN_OR_RETURN(actor::DenseLayer layer, DenseFromProto(proto, field));
    layers.push_back(std::move(layer));
  }
  return absl::OkStatus();
}

}  // namespace

v1::PolicyWeights WeightsToProto(const actor::PolicyWeights& weights) {
  v1::PolicyWeights proto;
  if (weights.image.has_value()) {
    const actor::ImageEncoderWeights& image = *weights.image;
    v1::ImageEncoder& encoder = *proto.mutable_image();
    encoder.set_height(image.height);
    encoder.set_width(image.width);
    encoder.set_channels(image.channels);
    for (const actor::ConvLayer& conv : image.convs) {
      v1::ConvLayer& out = *encoder.add_convs();
      *out.mutable_weight() =
          ToTensor(conv.weight, {conv.out_channels, conv.in_channels, conv.kernel, conv.kernel});
      *out.mutable_bias() = ToTensor(conv.bias);
      out.set_stride(conv.stride);
    }
    *encoder.mutable_linear() = DenseToProto(image.linear);
  }
  for (const actor::DenseLayer& layer : weights.context_layers) {
    *proto.add_context_layers() = DenseToProto(layer);
  }
  for (const actor::DenseLayer& layer : weights.layers) *proto.add_layers() = DenseToProto(layer);
  *proto.mutable_log_std() = ToTensor(weights.log_std);
  proto.set_num_actions(weights.num_actions);
  return proto;
}

absl::StatusOr<actor::PolicyWeights> WeightsFromProto(const v1::PolicyWeights& proto) {
  actor::PolicyWeights weights{.num_actions = proto.num_actions()};
  if (proto.has_image()) {
    const v1::ImageEncoder& encoder = proto.image();
    actor::ImageEncoderWeights& image = weights.image.emplace();
    image.height = encoder.height();
    image.width = encoder.width();
    image.channels = encoder.channels();
    for (const v1::ConvLayer& in : encoder.convs()) {
      const auto& shape = in.weight().shape();
      if (shape.size() != 4 || shape[2] != shape[3]) {
        return absl::InvalidArgumentError(
            "image.convs.weight must have shape [out_channels, in_channels, kernel, kernel]");
      }
      actor::ConvLayer conv{.in_channels = static_cast<int>(shape[1]),
                            .out_channels = static_cast<int>(shape[0]),
                            .kernel = static_cast<int>(shape[2]),
                            .stride = in.stride()};
      DCS_ASSIGN_OR_RETURN(conv.weight, FromTensor<float>(in.weight(), "image.convs.weight"));
      DCS_ASSIGN_OR_RETURN(conv.bias, FromTensor<float>(in.bias(), "image.convs.bias"));
      image.convs.push_back(std::move(conv));
    }
    DCS_ASSIGN_OR_RETURN(image.linear, DenseFromProto(encoder.linear(), "image.linear"));
  }
  DCS_RETURN_IF_ERROR(
      DenseLayersFromProto(proto.context_layers(), "context_layers", weights.context_layers));
  DCS_RETURN_IF_ERROR(DenseLayersFromProto(proto.layers(), "layers", weights.layers));
  DCS_ASSIGN_OR_RETURN(weights.log_std, FromTensor<float>(proto.log_std(), "log_std"));
  return weights;
}

absl::StatusOr<actor::PolicyNetwork> PolicyFromBytes(absl::string_view bytes) {
  v1::PolicyWeights proto;
  if (!proto.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    return absl::InvalidArgumentError(
        absl::StrCat("the policy's weights (", bytes.size(), " bytes) do not parse"));
  }
  DCS_ASSIGN_OR_RETURN(const actor::PolicyWeights weights, WeightsFromProto(proto));
  return actor::PolicyNetwork::Create(weights);
}

}  // namespace dcs::services
