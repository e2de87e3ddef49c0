// Copyright 2026 The DCS Authors.
//
// The golden run: seed 0 of configs/cartpole_length_pool7_static_blind.yaml, trained in one
// process on the pinned kernels (as `dcs train` trains it), gives exactly the evaluations and
// final weights recorded in tests/learner/data/golden_cartpole_static_blind_seed0.csv: every
// evaluation's split means and avg_combined written with %.17g, and an FNV-1a hash of the final
// parameters' bytes. It holds on every x86-64-v3 machine, Intel or AMD (docs/architecture.md §8),
// so CI guards that a run is a function of its config and seed wherever it runs.
//
// A change that changes a run's bits on purpose updates the file and says why in its commit
// message: DCS_UPDATE_GOLDEN=1 makes this test write the file it would have compared against.

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "actor/split.h"
#include "common/atomic_file.h"
#include "common/random.h"
#include "env/cartpole.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"
#include "learner/training_run.h"
#include "run/run_spec_yaml.h"

namespace dcs::learner {
namespace {

constexpr char kConfig[] = DCS_CONFIG_DIR "/cartpole_length_pool7_static_blind.yaml";
constexpr char kGolden[] = DCS_TEST_DATA_DIR "/golden_cartpole_static_blind_seed0.csv";

// The run as the golden file records it.
std::string Record(const TrainingResult& result) {
  std::string text = absl::StrCat(
      "# Seed 0 of configs/cartpole_length_pool7_static_blind.yaml in one process "
      "(tests/learner/golden_run_test.cc)\nstep,updates");
  for (const auto& [split, name] : actor::kSplitNames) absl::StrAppend(&text, ",", name);
  absl::StrAppend(&text, ",avg_combined\n");
  for (const actor::EvaluationResult& evaluation : result.state.evaluations) {
    absl::StrAppend(&text, evaluation.step, ",", evaluation.updates);
    for (double mean : evaluation.split_mean) absl::StrAppendFormat(&text, ",%.17g", mean);
    absl::StrAppendFormat(&text, ",%.17g\n", evaluation.avg_combined);
  }
  const absl::string_view bytes(reinterpret_cast<const char*>(result.parameters.data()),
                                result.parameters.size() * sizeof(float));
  absl::StrAppendFormat(&text, "parameters,%d,fnv1a64,%016x\n", result.parameters.size(),
                        Fnv1a64(bytes));
  return text;
}

TEST(GoldenRunTest, SeedZeroOfTheStaticBlindConfigGivesTheRecordedRun) {
  ASSERT_TRUE(PinTorchThreads(1).ok());
  absl::StatusOr<std::string> config = ReadFile(kConfig);
  ASSERT_TRUE(config.ok()) << config.status();
  absl::StatusOr<run::RunSpec> spec = run::ParseRunSpecYaml(*config, kConfig);
  ASSERT_TRUE(spec.ok()) << spec.status();
  ASSERT_EQ(spec->seed, 0u);
  absl::StatusOr<TrainingResult> result = Train<env::CartPole>(*spec, {});
  ASSERT_TRUE(result.ok()) << result.status();
  const std::string actual = Record(*result);

  if (std::getenv("DCS_UPDATE_GOLDEN") != nullptr) {
    ASSERT_TRUE(WriteFileAtomically(kGolden, actual).ok());
    GTEST_SKIP() << "wrote " << kGolden;
  }
  absl::StatusOr<std::string> golden = ReadFile(kGolden);
  ASSERT_TRUE(golden.ok()) << golden.status();
  const std::vector<absl::string_view> expected_lines = absl::StrSplit(*golden, '\n');
  const std::vector<absl::string_view> actual_lines = absl::StrSplit(actual, '\n');
  ASSERT_EQ(actual_lines.size(), expected_lines.size()) << actual;
  for (size_t i = 0; i < expected_lines.size(); ++i) {
    ASSERT_EQ(std::string(actual_lines[i]), std::string(expected_lines[i]))
        << "line " << i + 1 << " of " << kGolden << " (the numeric kernels: "
        << NumericFingerprint() << "). If the change of bits is deliberate, rerun with "
        << "DCS_UPDATE_GOLDEN=1 and say why in the commit message. The whole run:\n" << actual;
  }
}

}  // namespace
}  // namespace dcs::learner
