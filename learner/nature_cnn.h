// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_NATURE_CNN_H_
#define DCS_LEARNER_NATURE_CNN_H_

// Stable-Baselines3's NatureCNN on a batch of images, forward and backward, for PPO's update:
// 8x8/4 -> 32, 4x4/2 -> 64 and 3x3/1 -> 64 convolutions, each followed by ReLU, then a Linear
// layer and ReLU on their output flattened as torch flattens [channels, height, width].
//
// Each convolution is one matrix-matrix product: its weight, channel last
// (actor/conv_layout.h), times the batch's receptive fields laid side by side, one column per
// output position (im2col); its backward pass is two more, the gradient at the receptive fields
// added back onto the input's positions (col2im). Activations stay channel last, [channels x
// (image, y, x)] column-major, so a receptive field is `kernel` contiguous runs and a product's
// output is the next layer's input as it is. Eigen's products block by the pinned sizes
// (actor/eigen_blocking.h: the caller pins), so a pass gives the same bits on every x86-64-v3
// CPU, and the same bits whichever thread runs it.
//
// Parameters stay where the learner keeps and optimises them, in torch's layouts (a view of
// each is passed to every call), and gradients are written there.
//
// Thread-compatible: a NatureCnn is immutable; a Pass belongs to one thread.

#include <array>
#include <cstdint>
#include <span>

#include <Eigen/Core>

#include "actor/dense_forward.h"

namespace dcs::learner {

// One convolution on a channel-last input.
struct ConvShape {
  int in_height = 0;
  int in_width = 0;
  int in_channels = 0;
  int out_channels = 0;
  int kernel = 0;
  int stride = 1;
  int out_height() const { return (in_height - kernel) / stride + 1; }
  int out_width() const { return (in_width - kernel) / stride + 1; }
  int in_positions() const { return in_height * in_width; }
  int out_positions() const { return out_height() * out_width(); }
  int patch_size() const { return kernel * kernel * in_channels; }  // one receptive field
};

class NatureCnn {
 public:
  static constexpr int kConvs = 3;
  static constexpr int kLayers = kConvs + 1;  // the convolutions, then the Linear layer
  // The images of a forward pass not kept for a backward pass go through in chunks of this
  // many, which bounds the scratch (a chunk's receptive fields: 26 MB on CarRacing's images).
  static constexpr int kChunk = 64;

  // Each layer's weight and bias, or their gradients, in torch's layouts: a convolution's
  // [out][in][ky][kx] and [out]; the Linear layer's [features][flattened_size()] and [features].
  template <typename T>
  struct Tensors {
    std::array<std::span<T>, kLayers> weights;
    std::array<std::span<T>, kLayers> biases;
  };
  using Parameters = Tensors<const float>;
  using Gradients = Tensors<float>;

  // What a forward pass keeps for its backward pass, and scratch (reused by the next pass).
  struct Pass {
    int count = 0;
    std::array<actor::RowMajorMatrix, kConvs> weights;  // channel last, as of the forward pass
    Eigen::MatrixXf image;                              // [channels x (image, y, x)] in [0, 1]
    std::array<Eigen::MatrixXf, kConvs> columns;        // each convolution's receptive fields
    std::array<Eigen::MatrixXf, kConvs> outputs;        // after ReLU, channel last
    Eigen::MatrixXf flattened;                          // [flattened_size() x count]
    Eigen::MatrixXf features;                           // [features x count], after ReLU
    Eigen::MatrixXf d_linear;                       // the gradient before the Linear's ReLU
    Eigen::MatrixXf d_flattened;                    // at the Linear layer's input
    std::array<Eigen::MatrixXf, kConvs> d_outputs;  // at each convolution's output
    Eigen::MatrixXf d_columns;                      // at a convolution's receptive fields
    actor::RowMajorMatrix d_weight;                 // a convolution's, channel last
  };

  // NatureCNN on [height x width x channels] images, with `features` outputs.
  // REQUIRES: the image is at least 36 x 36 (its convolutions need that much), features > 0.
  NatureCnn(int height, int width, int channels, int features);

  const std::array<ConvShape, kConvs>& convs() const { return convs_; }
  int flattened_size() const;  // the Linear layer's inputs
  int feature_size() const { return features_; }
  int image_size() const;  // bytes

  // The features of `count` images (channel-last bytes, image after image, read as byte / 255
  // as torch's to(float).div(255)) into `features` [feature_size() x count]. With
  // `for_backward`, the batch goes through at once and `pass` keeps what Backward needs;
  // otherwise in chunks of kChunk images.
  // REQUIRES: images.size() == count * image_size().
  void Forward(const Parameters& parameters, std::span<const uint8_t> images, int count,
               bool for_backward, Pass& pass, Eigen::MatrixXf& features) const;

  // Writes every parameter's gradient from `d_features` [feature_size() x count], the gradient
  // at the features of `pass`: the last Forward with `for_backward`, of `parameters` unchanged.
  void Backward(const Parameters& parameters, const Eigen::Ref<const Eigen::MatrixXf>& d_features,
                Pass& pass, const Gradients& gradients) const;

 private:
  // One chunk of images through every layer, into pass (features into pass.features).
  void ForwardChunk(const Parameters& parameters, std::span<const uint8_t> images, int count,
                    Pass& pass) const;

  std::array<ConvShape, kConvs> convs_;
  int features_ = 0;
};

}  // namespace dcs::learner

#endif  // DCS_LEARNER_NATURE_CNN_H_
