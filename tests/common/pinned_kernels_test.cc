// Copyright 2026 The DCS Authors.
#include "common/pinned_kernels.h"

#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs {
namespace {

using ::testing::ElementsAre;

TEST(PinnedKernelEnvironmentTest, AppendsEveryPinnedVariableToAnEmptyEnvironment) {
  const char* const environment[] = {nullptr};
  EXPECT_THAT(PinnedKernelEnvironment(environment),
              ElementsAre("OPENBLAS_CORETYPE=Haswell", "OPENBLAS_NUM_THREADS=1",
                          "ATEN_CPU_CAPABILITY=avx2"));
}

TEST(PinnedKernelEnvironmentTest, KeepsEveryOtherVariableInOrder) {
  const char* const environment[] = {"PATH=/usr/bin", "HOME=/home/dcs", "EMPTY=", nullptr};
  EXPECT_THAT(PinnedKernelEnvironment(environment),
              ElementsAre("PATH=/usr/bin", "HOME=/home/dcs", "EMPTY=", "OPENBLAS_CORETYPE=Haswell",
                          "OPENBLAS_NUM_THREADS=1", "ATEN_CPU_CAPABILITY=avx2"));
}

// A user's own choice (a faster core on this machine) gives way to the pinned one, where it
// stood.
TEST(PinnedKernelEnvironmentTest, ReplacesOtherValuesWhereTheyStand) {
  const char* const environment[] = {"ATEN_CPU_CAPABILITY=avx512", "PATH=/bin",
                                     "OPENBLAS_CORETYPE=SkylakeX",
                                     "OPENBLAS_NUM_THREADS=", nullptr};
  EXPECT_THAT(PinnedKernelEnvironment(environment),
              ElementsAre("ATEN_CPU_CAPABILITY=avx2", "PATH=/bin", "OPENBLAS_CORETYPE=Haswell",
                          "OPENBLAS_NUM_THREADS=1"));
}

TEST(PinnedKernelEnvironmentTest, LeavesAPinnedEnvironmentAsItIs) {
  const char* const environment[] = {"OPENBLAS_CORETYPE=Haswell", "OPENBLAS_NUM_THREADS=1",
                                     "ATEN_CPU_CAPABILITY=avx2", "LANG=C.UTF-8", nullptr};
  EXPECT_THAT(PinnedKernelEnvironment(environment),
              ElementsAre("OPENBLAS_CORETYPE=Haswell", "OPENBLAS_NUM_THREADS=1",
                          "ATEN_CPU_CAPABILITY=avx2", "LANG=C.UTF-8"));
}

// A variable is named by the whole text before its first '=': longer names, a name in a
// value, and an entry without '=' are other variables.
TEST(PinnedKernelEnvironmentTest, MatchesWholeNamesOnly) {
  const char* const environment[] = {"OPENBLAS_CORETYPE_X=1", "XOPENBLAS_CORETYPE=1",
                                     "NOTE=OPENBLAS_CORETYPE=Zen", "OPENBLAS_CORETYPE", nullptr};
  EXPECT_THAT(
      PinnedKernelEnvironment(environment),
      ElementsAre("OPENBLAS_CORETYPE_X=1", "XOPENBLAS_CORETYPE=1", "NOTE=OPENBLAS_CORETYPE=Zen",
                  "OPENBLAS_CORETYPE", "OPENBLAS_CORETYPE=Haswell", "OPENBLAS_NUM_THREADS=1",
                  "ATEN_CPU_CAPABILITY=avx2"));
}

// execve takes the array as it is: a second entry must not bring the old value back to a
// reader that takes the last.
TEST(PinnedKernelEnvironmentTest, DropsASecondEntryOfAPinnedName) {
  const char* const environment[] = {"OPENBLAS_CORETYPE=Zen", "PATH=/bin",
                                     "OPENBLAS_CORETYPE=SkylakeX", nullptr};
  EXPECT_THAT(PinnedKernelEnvironment(environment),
              ElementsAre("OPENBLAS_CORETYPE=Haswell", "PATH=/bin", "OPENBLAS_NUM_THREADS=1",
                          "ATEN_CPU_CAPABILITY=avx2"));
}

}  // namespace
}  // namespace dcs
