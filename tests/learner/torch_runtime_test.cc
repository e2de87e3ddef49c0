// Copyright 2026 The DCS Authors.
#include "learner/torch_runtime.h"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <ATen/Parallel.h>

#include "absl/status/status.h"
#include "gtest/gtest.h"

namespace dcs::learner {
namespace {

TEST(PinTorchThreadsTest, RejectsLessThanOneThread) {
  EXPECT_EQ(PinTorchThreads(0).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(PinTorchThreads(-3).code(), absl::StatusCode::kInvalidArgument);
}

// libtorch's thread pools are process-global and the inter-op pool can be sized only once,
// so the order-dependent checks live in this one test.
TEST(PinTorchThreadsTest, PinsOnceThenRefusesToResize) {
  const absl::Status first = PinTorchThreads(1);
  ASSERT_TRUE(first.ok()) << first;
  EXPECT_EQ(at::get_num_threads(), 1);
  EXPECT_EQ(at::get_num_interop_threads(), 1);

  const absl::Status second = PinTorchThreads(2);
  EXPECT_EQ(second.code(), absl::StatusCode::kFailedPrecondition) << second;
  // A refused call changes nothing.
  EXPECT_EQ(at::get_num_interop_threads(), 1);
  EXPECT_EQ(at::get_num_threads(), 1);
}

TEST(LibraryVersionsTest, ReportsLibtorch) {
  const std::vector<LibraryVersion> libraries = LibraryVersions();
  const auto libtorch = std::find_if(libraries.begin(), libraries.end(),
                                     [](const LibraryVersion& l) { return l.name == "libtorch"; });
  ASSERT_NE(libtorch, libraries.end());
  EXPECT_FALSE(libtorch->version.empty());
  EXPECT_NE(libtorch->version.find('.'), std::string::npos) << libtorch->version;
}

// bootstrap installs the serial OpenBLAS as libtorch's BLAS.
TEST(BlasCoreTest, ReportsTheOpenBlasCoreInUse) {
  const std::string core = BlasCoreName();
  ASSERT_FALSE(core.empty());
  const std::vector<LibraryVersion> libraries = LibraryVersions();
  EXPECT_NE(std::find(libraries.begin(), libraries.end(), LibraryVersion{"openblas core", core}),
            libraries.end());
}

TEST(BlasCoreTest, AChosenCoreIsLeftAlone) {
  ASSERT_EQ(setenv("OPENBLAS_CORETYPE", "Haswell", /*overwrite=*/1), 0);
  EXPECT_EQ(BetterBlasCore(), std::nullopt);
  ASSERT_EQ(unsetenv("OPENBLAS_CORETYPE"), 0);
  // Without it, a better core is named only when OpenBLAS fell back to its generic one.
  if (BlasCoreName() != "Prescott") {
    EXPECT_EQ(BetterBlasCore(), std::nullopt);
  }
}

}  // namespace
}  // namespace dcs::learner
