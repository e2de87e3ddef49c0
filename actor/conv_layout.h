// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_CONV_LAYOUT_H_
#define DCS_ACTOR_CONV_LAYOUT_H_

// A convolution's weight in the two layouts DCS keeps it in: torch's, [out][in][ky][kx], where
// the learner stores and optimises it; and channel last, [out x (ky, kx, in)], the order of a
// receptive field read from a channel-last image ([y][x][channel], as images come), where
// DCS's convolutions multiply it (actor/image_encoder.h, learner/nature_cnn.h). In that order a
// receptive field is `kernel` runs of kernel * in contiguous floats.
// Thread-safe (free functions on their arguments).

#include <span>

#include <Eigen/Core>

#include "actor/dense_forward.h"

namespace dcs::actor {

// torch's weight as [out x kernel * kernel * in], channel last. `weight` is resized.
// REQUIRES: torch_weight.size() == out * in * kernel * kernel.
void ToChannelLast(std::span<const float> torch_weight, int out, int in, int kernel,
                   RowMajorMatrix& weight);

// The inverse: a channel-last [out x kernel * kernel * in] matrix (a weight, or its gradient)
// into torch's layout.
// REQUIRES: weight is [out x kernel * kernel * in], torch_weight.size() == weight.size().
void ToTorchLayout(const RowMajorMatrix& weight, int in, int kernel,
                   std::span<float> torch_weight);

}  // namespace dcs::actor

#endif  // DCS_ACTOR_CONV_LAYOUT_H_
