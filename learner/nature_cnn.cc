// Copyright 2026 The DCS Authors.
#include "learner/nature_cnn.h"

#include <algorithm>

#include "actor/conv_layout.h"

namespace dcs::learner {
namespace {

// NatureCNN's convolutions: output channels, kernel, stride.
constexpr std::array<std::array<int, 3>, NatureCnn::kConvs> kNatureConvs = {
    {{32, 8, 4}, {64, 4, 2}, {64, 3, 1}}};

using ConstMap = Eigen::Map<const Eigen::MatrixXf>;
using RowMajorMap = Eigen::Map<const actor::RowMajorMatrix>;

// Calls visit(offset) for each row of each receptive field of `count` channel-last inputs
// [in_channels x (image, y, x)]: output position (image, oy, ox) after output position, row ky
// after row ky, `offset` where the row's kernel * in_channels contiguous floats start.
template <typename Visit>
void ForEachFieldRow(const ConvShape& conv, int count, Visit visit) {
  for (int image = 0; image < count; ++image) {
    for (int oy = 0; oy < conv.out_height(); ++oy) {
      for (int ox = 0; ox < conv.out_width(); ++ox) {
        for (int ky = 0; ky < conv.kernel; ++ky) {
          visit((static_cast<Eigen::Index>(image) * conv.in_height + oy * conv.stride + ky) *
                    conv.in_width * conv.in_channels +
                static_cast<Eigen::Index>(ox) * conv.stride * conv.in_channels);
        }
      }
    }
  }
}

// The receptive fields of `count` inputs, one column per output position, rows in the order
// (ky, kx, channel).
void Im2Col(const ConvShape& conv, const Eigen::MatrixXf& input, int count,
            Eigen::MatrixXf& columns) {
  columns.resize(conv.patch_size(), static_cast<Eigen::Index>(count) * conv.out_positions());
  const int run = conv.kernel * conv.in_channels;
  float* out = columns.data();
  ForEachFieldRow(conv, count,
                  [&](Eigen::Index offset) { out = std::copy_n(input.data() + offset, run, out); });
}

// The inverse of Im2Col's gather: each receptive field's gradient added onto the positions it
// was read from, into `d_input` [in_channels x (image, y, x)], overwritten.
void Col2Im(const ConvShape& conv, const Eigen::MatrixXf& d_columns, int count,
            Eigen::MatrixXf& d_input) {
  d_input.setZero(conv.in_channels, static_cast<Eigen::Index>(count) * conv.in_positions());
  const int run = conv.kernel * conv.in_channels;
  const float* in = d_columns.data();
  ForEachFieldRow(conv, count, [&](Eigen::Index offset) {
    float* row = d_input.data() + offset;
    for (int i = 0; i < run; ++i) row[i] += in[i];
    in += run;
  });
}

Eigen::Map<const Eigen::VectorXf> Vector(std::span<const float> values) {
  return {values.data(), static_cast<Eigen::Index>(values.size())};
}

// Each of `count` images' [rows x cols] block of `from` (column-major, image after image),
// transposed into `to`: between a channel-last output [channels x positions] and torch's
// flatten of it, [positions x channels], either way.
void TransposeEachImage(const float* from, int rows, int cols, int count, float* to) {
  const Eigen::Index size = static_cast<Eigen::Index>(rows) * cols;
  for (int image = 0; image < count; ++image) {
    Eigen::Map<Eigen::MatrixXf>(to + image * size, cols, rows) =
        ConstMap(from + image * size, rows, cols).transpose();
  }
}

}  // namespace

NatureCnn::NatureCnn(int height, int width, int channels, int features) : features_(features) {
  for (int i = 0; i < kConvs; ++i) {
    const auto [out_channels, kernel, stride] = kNatureConvs[i];
    convs_[i] = {.in_height = height,
                 .in_width = width,
                 .in_channels = channels,
                 .out_channels = out_channels,
                 .kernel = kernel,
                 .stride = stride};
    height = convs_[i].out_height();
    width = convs_[i].out_width();
    channels = out_channels;
  }
}

int NatureCnn::flattened_size() const {
  return convs_.back().out_positions() * convs_.back().out_channels;
}

int NatureCnn::image_size() const {
  return convs_.front().in_positions() * convs_.front().in_channels;
}

void NatureCnn::Forward(const Parameters& parameters, std::span<const uint8_t> images, int count,
                        bool for_backward, Pass& pass, Eigen::MatrixXf& features) const {
  for (int i = 0; i < kConvs; ++i) {
    actor::ToChannelLast(parameters.weights[i], convs_[i].out_channels, convs_[i].in_channels,
                         convs_[i].kernel, pass.weights[i]);
  }
  features.resize(features_, count);
  const int chunk = for_backward ? count : kChunk;
  for (int start = 0; start < count; start += chunk) {
    const int size = std::min(chunk, count - start);
    ForwardChunk(parameters,
                 images.subspan(static_cast<size_t>(start) * image_size(),
                                static_cast<size_t>(size) * image_size()),
                 size, pass);
    features.middleCols(start, size) = pass.features;
  }
}

void NatureCnn::ForwardChunk(const Parameters& parameters, std::span<const uint8_t> images,
                             int count, Pass& pass) const {
  pass.count = count;
  pass.image.resize(convs_.front().in_channels,
                    static_cast<Eigen::Index>(count) * convs_.front().in_positions());
  std::transform(images.begin(), images.end(), pass.image.data(),
                 [](uint8_t byte) { return static_cast<float>(byte) / 255.0f; });
  for (int i = 0; i < kConvs; ++i) {
    Im2Col(convs_[i], i == 0 ? pass.image : pass.outputs[i - 1], count, pass.columns[i]);
    Eigen::MatrixXf& out = pass.outputs[i];
    out.resize(convs_[i].out_channels, pass.columns[i].cols());
    out.colwise() = Vector(parameters.biases[i]);  // the product is added to the bias
    out.noalias() += pass.weights[i] * pass.columns[i];
    actor::Activate(actor::Activation::kRelu, out);
  }
  // torch's flatten of each image's [channels, y, x]: its channel-last block transposed.
  const ConvShape& last = convs_.back();
  pass.flattened.resize(flattened_size(), count);
  TransposeEachImage(pass.outputs.back().data(), last.out_channels, last.out_positions(), count,
                     pass.flattened.data());
  pass.features.resize(features_, count);
  pass.features.colwise() = Vector(parameters.biases.back());
  pass.features.noalias() +=
      RowMajorMap(parameters.weights.back().data(), features_, flattened_size()) *
      pass.flattened;
  actor::Activate(actor::Activation::kRelu, pass.features);
}

void NatureCnn::Backward(const Parameters& parameters,
                         const Eigen::Ref<const Eigen::MatrixXf>& d_features, Pass& pass,
                         const Gradients& gradients) const {
  const int count = pass.count;
  const auto bias_gradient = [](const Eigen::MatrixXf& d, std::span<float> bias) {
    Eigen::Map<Eigen::VectorXf>(bias.data(), static_cast<Eigen::Index>(bias.size())) =
        d.rowwise().sum();
  };

  pass.d_linear = d_features;
  actor::ActivationGradient(actor::Activation::kRelu, pass.features, pass.d_linear);
  Eigen::Map<actor::RowMajorMatrix>(gradients.weights.back().data(), features_,
                                    flattened_size())
      .noalias() = pass.d_linear * pass.flattened.transpose();
  bias_gradient(pass.d_linear, gradients.biases.back());
  pass.d_flattened.noalias() =
      RowMajorMap(parameters.weights.back().data(), features_, flattened_size()).transpose() *
      pass.d_linear;
  // The flattened gradient back to channel last.
  const ConvShape& last = convs_.back();
  Eigen::MatrixXf& d_last = pass.d_outputs.back();
  d_last.resize(last.out_channels, static_cast<Eigen::Index>(count) * last.out_positions());
  TransposeEachImage(pass.d_flattened.data(), last.out_positions(), last.out_channels, count,
                     d_last.data());

  for (int i = kConvs - 1; i >= 0; --i) {
    const ConvShape& conv = convs_[i];
    Eigen::MatrixXf& d_output = pass.d_outputs[i];  // becomes the gradient before ReLU
    actor::ActivationGradient(actor::Activation::kRelu, pass.outputs[i], d_output);
    pass.d_weight.noalias() = d_output * pass.columns[i].transpose();
    actor::ToTorchLayout(pass.d_weight, conv.in_channels, conv.kernel, gradients.weights[i]);
    bias_gradient(d_output, gradients.biases[i]);
    if (i == 0) break;  // the image has no gradient
    pass.d_columns.noalias() = pass.weights[i].transpose() * d_output;
    Col2Im(conv, pass.d_columns, count, pass.d_outputs[i - 1]);
  }
}

}  // namespace dcs::learner
