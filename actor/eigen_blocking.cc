// Copyright 2026 The DCS Authors.
#include "actor/eigen_blocking.h"

#include <Eigen/Core>

namespace dcs::actor {

void PinEigenBlocking() {
  // A function-local static: set once, and every caller's later products happen after it.
  [[maybe_unused]] static const bool pinned = [] {
    Eigen::setCpuCacheSizes(kEigenL1Bytes, kEigenL2Bytes, kEigenL3Bytes);
    return true;
  }();
}

}  // namespace dcs::actor
