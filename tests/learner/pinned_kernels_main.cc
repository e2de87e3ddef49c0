// Copyright 2026 The DCS Authors.
//
// main() of learner tests that compute on the kernels every training process pins
// (learner/torch_runtime.h): PinNumericKernels first, as the programs do (it may run the test
// program again with the pinned variables set, with the same arguments).

#include <iostream>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"

int main(int argc, char** argv) {
  dcs::learner::PinNumericKernels([](absl::string_view line) { std::cerr << line << "\n"; });
  testing::InitGoogleMock(&argc, argv);
  return RUN_ALL_TESTS();
}
