// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_IMAGE_ENCODER_H_
#define DCS_ACTOR_IMAGE_ENCODER_H_

// NatureCNN inference in Eigen, for image policies on actors and in `dcs train`: the same
// function as the learner's torch encoder (tested to 1e-5), computed with matrix-vector
// products only, each image alone. Their summation order is fixed when the program is compiled
// (Eigen's matrix-matrix products block by the cache sizes of the CPU they run on unless pinned:
// actor/eigen_blocking.h), so an encoding is the same on any x86-64-v3 machine running the same
// binary (docs/architecture.md §8), and does not depend on the other images of a batch.
//
// Activations stay channel last ([height * width][channels], as the image comes), so the
// receptive field of a convolution's output is `kernel` runs of kernel * channels contiguous
// floats; the weights are permuted once, at creation, to match.
//
// Thread-compatible: one instance per thread (it owns its scratch).

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "absl/status/statusor.h"
#include "actor/dense_forward.h"
#include "actor/policy_weights.h"

namespace dcs::actor {

class ImageEncoder {
 public:
  // INVALID_ARGUMENT if a layer does not fit the one before it or its sizes are wrong (naming
  // the layer), or the linear layer is not followed by ReLU.
  static absl::StatusOr<ImageEncoder> Create(const ImageEncoderWeights& weights);

  int image_size() const { return image_size_; }                              // bytes
  int feature_size() const { return static_cast<int>(linear_bias_.size()); }  // floats

  // REQUIRES: image.size() == image_size(), features.size() == feature_size().
  void Encode(std::span<const uint8_t> image, std::span<float> features);

 private:
  using Matrix = RowMajorMatrix;
  struct Conv {
    int kernel = 0;
    int stride = 0;
    int in_width = 0;  // of its input
    int out_height = 0;
    int out_width = 0;
    Matrix weight;  // out_channels x (ky, kx, in_channel)
    Eigen::VectorXf bias;
  };

  ImageEncoder() = default;

  int image_size_ = 0;
  std::vector<Conv> convs_;
  Matrix linear_weight_;  // its inputs in channel-last order
  Eigen::VectorXf linear_bias_;
  // Scratch: each convolution's input, [positions][channels], and the last one's output.
  std::vector<Matrix> activations_;
  Eigen::VectorXf patch_;  // one receptive field
};

}  // namespace dcs::actor

#endif  // DCS_ACTOR_IMAGE_ENCODER_H_
