// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_POLICY_WEIGHTS_H_
#define DCS_ACTOR_POLICY_WEIGHTS_H_

// The actor half of a policy network as the learner exports it (learner/actor_critic.h) and
// actors load it (actor/policy_network.h): plain data in torch's layouts, row-major (a Linear's
// weight is [outputs, inputs], a Conv2d's [out_channels, in_channels, kernel, kernel]).
// Thread-compatible (plain data).

#include <optional>
#include <vector>

namespace dcs::actor {

// What follows a layer.
enum class Activation { kNone, kTanh, kRelu };

// One dense layer: y = activation(W x + b).
struct DenseLayer {
  int inputs = 0;
  int outputs = 0;
  std::vector<float> weight;  // outputs x inputs
  std::vector<float> bias;    // outputs
  Activation activation = Activation::kTanh;
};

// One convolution with a square kernel, no padding and no dilation, then ReLU (NatureCNN's
// only kind).
struct ConvLayer {
  int in_channels = 0;
  int out_channels = 0;
  int kernel = 0;
  int stride = 1;
  std::vector<float> weight;  // out_channels x in_channels x kernel x kernel
  std::vector<float> bias;    // out_channels
};

// SB3's NatureCNN on an image of height x width x channels bytes (channel last) scaled to
// [0, 1]: the convolutions, then `linear` on their output flattened channel-first (torch's
// flatten of [channels, height, width]).
struct ImageEncoderWeights {
  int height = 0;
  int width = 0;
  int channels = 0;
  std::vector<ConvLayer> convs;
  DenseLayer linear;
};

// The actor network: for an image policy, the features are the encoder's output followed by
// the flat inputs (SB3's CombinedExtractor), or by their output through `context_layers` (the
// context's own branch, when it has one); otherwise the flat inputs. Then `layers`, the hidden
// layers and the head (no activation) giving categorical logits or a Gaussian mean.
struct PolicyWeights {
  std::optional<ImageEncoderWeights> image;
  std::vector<DenseLayer> context_layers;  // image policies only; may be empty
  std::vector<DenseLayer> layers;
  std::vector<float> log_std;  // continuous actions only, one per action dimension
  int num_actions = 0;         // discrete: the number of actions; continuous: 0
};

}  // namespace dcs::actor

#endif  // DCS_ACTOR_POLICY_WEIGHTS_H_
