// Copyright 2026 The DCS Authors.
#include "learner/torch_runtime.h"

#include <ATen/Context.h>
#include <ATen/Parallel.h>
#include <torch/version.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/scoped_variable.h"

namespace dcs::learner {
namespace {

using ::dcs::testing::ScopedVariable;
using ::testing::AnyOf;
using ::testing::Contains;
using ::testing::ElementsAre;
using ::testing::EndsWith;
using ::testing::Field;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::StrEq;

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

TEST(UnpinnedKernelVariablesTest, NamesEachVariableThatIsUnsetOrDiffers) {
  const auto name = [](const char* n) { return Field(&KernelVariable::name, StrEq(n)); };
  {
    ScopedVariable blas("OPENBLAS_CORETYPE", std::nullopt);
    ScopedVariable threads("OPENBLAS_NUM_THREADS", std::nullopt);
    ScopedVariable aten("ATEN_CPU_CAPABILITY", std::nullopt);
    EXPECT_THAT(UnpinnedKernelVariables(),
                ElementsAre(name("OPENBLAS_CORETYPE"), name("OPENBLAS_NUM_THREADS"),
                            name("ATEN_CPU_CAPABILITY")));
  }
  {
    ScopedVariable blas("OPENBLAS_CORETYPE", "SkylakeX");
    ScopedVariable threads("OPENBLAS_NUM_THREADS", "1");
    ScopedVariable aten("ATEN_CPU_CAPABILITY", "avx2");
    EXPECT_THAT(UnpinnedKernelVariables(), ElementsAre(name("OPENBLAS_CORETYPE")));
  }
  {
    ScopedVariable blas("OPENBLAS_CORETYPE", "Haswell");
    ScopedVariable threads("OPENBLAS_NUM_THREADS", "2");
    ScopedVariable aten("ATEN_CPU_CAPABILITY", "avx512");
    EXPECT_THAT(UnpinnedKernelVariables(),
                ElementsAre(name("OPENBLAS_NUM_THREADS"), name("ATEN_CPU_CAPABILITY")));
  }
  {
    ScopedVariable blas("OPENBLAS_CORETYPE", "Haswell");
    ScopedVariable threads("OPENBLAS_NUM_THREADS", "1");
    ScopedVariable aten("ATEN_CPU_CAPABILITY", "avx2");
    EXPECT_THAT(UnpinnedKernelVariables(), IsEmpty());
  }
}

// In a process started with the pinned variables there is nothing to restart for: the call
// returns and says nothing. (The restart itself is checked through a `dcs-train` started
// without them: tests/integration/train_cli_test.cc.)
TEST(PinNumericKernelsTest, LeavesAPinnedProcessRunning) {
  ScopedVariable blas("OPENBLAS_CORETYPE", "Haswell");
  ScopedVariable threads("OPENBLAS_NUM_THREADS", "1");
  ScopedVariable aten("ATEN_CPU_CAPABILITY", "avx2");
  std::vector<std::string> notes;
  PinNumericKernels([&notes](absl::string_view note) { notes.emplace_back(note); });
  EXPECT_THAT(notes, IsEmpty());
}

TEST(NumericFingerprintTest, NamesTheLibraryAndTheKernelsInUse) {
  EXPECT_THAT(AtenCpuCapability(), AnyOf("default", "avx2", "avx512"));
  const std::string fingerprint = NumericFingerprint();
  EXPECT_THAT(fingerprint, HasSubstr(absl::StrCat("libtorch ", TORCH_VERSION, ", ")));
  EXPECT_THAT(fingerprint, HasSubstr(absl::StrCat("openblas ", BlasCoreName(), ", ")));
  EXPECT_THAT(fingerprint, EndsWith(absl::StrCat("aten ", AtenCpuCapability())));
}

// OpenBLAS and ATen read their variables when the process starts, so these checks run in a
// process started with them: a death test's child, which the "threadsafe" style starts anew
// (with this test's environment) rather than forking.
void ExpectFingerprintOfAProcessStartedWith(const char* blas_core, const char* aten_capability,
                                            const std::string& expected) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  ScopedVariable blas("OPENBLAS_CORETYPE", blas_core);
  ScopedVariable aten("ATEN_CPU_CAPABILITY", aten_capability);
  EXPECT_EXIT(
      {
        std::cerr << "fingerprint: " << NumericFingerprint() << std::endl;
        std::exit(0);
      },
      ::testing::ExitedWithCode(0), expected);
}

TEST(NumericFingerprintTest, NamesThePinnedKernelsInAProcessStartedWithThem) {
  ExpectFingerprintOfAProcessStartedWith("Haswell", "avx2", "openblas Haswell, aten avx2\n");
}

// The same with other kernels: the fingerprint reads what is in effect, not what DCS pins.
TEST(NumericFingerprintTest, NamesOtherKernelsInAProcessStartedWithThem) {
  ExpectFingerprintOfAProcessStartedWith("Prescott", "default",
                                         "openblas Prescott, aten default\n");
}

TEST(LibraryVersionsTest, ReportsLibtorchAndItsKernels) {
  const std::vector<LibraryVersion> libraries = LibraryVersions();
  const auto libtorch = std::find_if(libraries.begin(), libraries.end(),
                                     [](const LibraryVersion& l) { return l.name == "libtorch"; });
  ASSERT_NE(libtorch, libraries.end());
  EXPECT_FALSE(libtorch->version.empty());
  EXPECT_NE(libtorch->version.find('.'), std::string::npos) << libtorch->version;
  EXPECT_THAT(libraries, Contains(LibraryVersion{"aten cpu capability", AtenCpuCapability()}));
}

// bootstrap installs the serial OpenBLAS as libtorch's BLAS.
TEST(BlasCoreTest, ReportsTheOpenBlasCoreInUse) {
  const std::string core = BlasCoreName();
  ASSERT_FALSE(core.empty());
  EXPECT_THAT(LibraryVersions(), Contains(LibraryVersion{"openblas core", core}));
}

}  // namespace
}  // namespace dcs::learner
