// Copyright 2026 The DCS Authors.
#include "actor/conv_layout.h"

#include <cstddef>

namespace dcs::actor {
namespace {

// Where torch keeps the weight that channel last is at (o, (ky * kernel + kx) * in + c).
size_t TorchIndex(int o, int c, int ky, int kx, int in, int kernel) {
  return ((static_cast<size_t>(o) * in + c) * kernel + ky) * kernel + kx;
}

}  // namespace

void ToChannelLast(std::span<const float> torch_weight, int out, int in, int kernel,
                   RowMajorMatrix& weight) {
  weight.resize(out, static_cast<Eigen::Index>(kernel) * kernel * in);
  for (int o = 0; o < out; ++o) {
    for (int ky = 0; ky < kernel; ++ky) {
      for (int kx = 0; kx < kernel; ++kx) {
        for (int c = 0; c < in; ++c) {
          weight(o, (ky * kernel + kx) * in + c) =
              torch_weight[TorchIndex(o, c, ky, kx, in, kernel)];
        }
      }
    }
  }
}

void ToTorchLayout(const RowMajorMatrix& weight, int in, int kernel,
                   std::span<float> torch_weight) {
  for (int o = 0; o < weight.rows(); ++o) {
    for (int ky = 0; ky < kernel; ++ky) {
      for (int kx = 0; kx < kernel; ++kx) {
        for (int c = 0; c < in; ++c) {
          torch_weight[TorchIndex(o, c, ky, kx, in, kernel)] =
              weight(o, (ky * kernel + kx) * in + c);
        }
      }
    }
  }
}

}  // namespace dcs::actor
