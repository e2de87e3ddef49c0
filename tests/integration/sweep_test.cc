// Copyright 2026 The DCS Authors.
//
// Sweeps end to end, with real processes on loopback and the `dcs` client: a sweep submitted
// with `dcs submit` runs to completion, `dcs report` tabulates it and `dcs plot` draws it (its
// index.html looked at in headless Chromium, as `make demo`'s is); a sweep whose coordinator is
// killed (SIGKILL) mid-way and restarted on its data directory gives the same report; a bad
// spec is refused whole, every problem named, and nothing of it is stored.

#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/run_client.h"
#include "tests/integration/browser.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {
namespace {

using ::testing::HasSubstr;

constexpr absl::Duration kLease = absl::Seconds(1);
constexpr absl::Duration kTimeout = absl::Seconds(5);


// Two problems in two places: a negative amplitude and an unknown family.
constexpr char kBadSpec[] = R"(seeds: 2
env: cartpole
evaluation: {freq: 512, episodes: 2, contexts: {id: [0.5]}}
conditions:
  - name: static
  - schedule: {family: sinusoidal, amplitude_frac: -0.5, period: 40}
  - schedule: {family: teleport}
)";

std::string WriteSpec(const std::string& text) {
  const std::string path = testing::MakeTempDir() + "/small.yaml";
  EXPECT_TRUE(WriteFileAtomically(path, text).ok());
  return path;
}

// Waits until sweep `sweep_id` has at least `completed` completed runs, or has ended.
void WaitForCompleted(const ClusterProcesses& cluster, const std::string& sweep_id,
                      int completed) {
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(4));
  while (absl::Now() < deadline) {
    absl::StatusOr<v1::GetSweepResponse> sweep =
        services::cli::GetSweep(cluster.coordinator_address(), sweep_id, kTimeout);
    if (sweep.ok() && (sweep->sweep().completed() >= completed ||
                       sweep->sweep().state() == v1::SWEEP_STATE_COMPLETED)) {
      return;
    }
    absl::SleepFor(absl::Milliseconds(100));
  }
  FAIL() << sweep_id << " did not complete " << completed << " runs; logs in " << cluster.dir();
}

TEST(SweepTest, ASweepSurvivesItsCoordinatorsDeathAndReportsTheSame) {
  const std::string spec = WriteSpec(EightRunSweepSpec("small", 1536, 512));

  // Undisturbed: `dcs submit --watch` follows it to its end.
  ClusterProcesses calm(kLease);
  StartCoordinatorLearnerAndActors(calm);
  const RunResult submitted =
      DcsAt({"submit", spec, "--watch"}, calm.coordinator_address(), absl::Minutes(5));
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output << "; logs in " << calm.dir();
  EXPECT_THAT(submitted.output, HasSubstr("sweep-1 small: completed, 8/8 runs done"));
  const std::string undisturbed = SweepReports(calm, "sweep-1");
  EXPECT_THAT(undisturbed, HasSubstr("static"));
  EXPECT_THAT(undisturbed, HasSubstr("sinusoidal amplitude_frac=0.5"));
  const std::string figures = calm.dir() + "/figures";
  const RunResult plotted =
      DcsAt({"plot", "sweep-1", "--out", figures}, calm.coordinator_address());
  ASSERT_EQ(plotted.exit_code, 0) << plotted.output;
  EXPECT_THAT(plotted.output, HasSubstr(figures + "/index.html"));
  const std::vector<std::string> images = LoadedImages(figures + "/index.html");
  EXPECT_EQ(images.size(), 4u);  // learning curves, context returns, heatmap, profiles
  for (const std::string& image : images) EXPECT_THAT(image, HasSubstr(" loaded ")) << image;

  // The coordinator killed once two runs are done, restarted on its data directory.
  ClusterProcesses faulty(kLease);
  StartCoordinatorLearnerAndActors(faulty);
  const RunResult queued = DcsAt({"submit", spec}, faulty.coordinator_address());
  ASSERT_EQ(queued.exit_code, 0) << queued.output;
  EXPECT_THAT(queued.output, HasSubstr("sweep-1"));
  WaitForCompleted(faulty, "sweep-1", 2);
  faulty.Kill("coordinator");
  absl::SleepFor(2 * kLease);
  faulty.StartCoordinator();
  const RunResult watched =
      DcsAt({"watch", "sweep-1"}, faulty.coordinator_address(), absl::Minutes(5));
  ASSERT_EQ(watched.exit_code, 0) << watched.output << "; logs in " << faulty.dir();
  EXPECT_EQ(SweepReports(faulty, "sweep-1"), undisturbed);
}

TEST(SweepTest, ABadSpecIsRefusedWholeWithEveryProblemAndNothingIsStored) {
  ClusterProcesses cluster(kLease);
  cluster.StartCoordinator();
  const RunResult refused = DcsAt({"submit", WriteSpec(kBadSpec)}, cluster.coordinator_address());
  EXPECT_EQ(refused.exit_code, 65) << refused.output;  // EX_DATAERR
  EXPECT_THAT(refused.output, HasSubstr("INVALID_ARGUMENT"));
  EXPECT_THAT(refused.output, HasSubstr("2 problems"));
  EXPECT_THAT(refused.output, HasSubstr("conditions[1].schedule.amplitude_frac: line 6"));
  EXPECT_THAT(refused.output, HasSubstr("conditions[2].schedule: line 7"));
  EXPECT_THAT(refused.output, HasSubstr("teleport"));

  absl::StatusOr<std::vector<v1::Sweep>> sweeps =
      services::cli::ListSweeps(cluster.coordinator_address(), kTimeout);
  absl::StatusOr<std::vector<v1::Run>> runs =
      services::cli::ListRuns(cluster.coordinator_address(), kTimeout);
  ASSERT_TRUE(sweeps.ok() && runs.ok());
  EXPECT_TRUE(sweeps->empty());
  EXPECT_TRUE(runs->empty());
}

}  // namespace
}  // namespace dcs::integration
