// Copyright 2026 The DCS Authors.
//
// Sweeps end to end, with real processes on loopback and the `dcs` client: a sweep submitted
// with `dcs submit` runs to completion, `dcs report` tabulates it and `dcs plot` draws it (its
// index.html looked at in headless Chromium, as `make demo`'s is); a sweep whose coordinator is
// killed (SIGKILL) mid-way and restarted on its data directory gives the same report, and so
// does a coordinator restored from a `dcs backup` taken mid-way (docs/deploy.md, Backups); a bad
// spec is refused whole, every problem named, and nothing of it is stored.

#include <filesystem>
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

// Copies the run files under `from` into `to` while a coordinator may be writing them, as
// `rsync -a` would: a file that vanishes (an old checkpoint pruned) is skipped, and so is a
// temporary file (common/atomic_file.h) not yet renamed into place.
void CopyRunFiles(const std::filesystem::path& from, const std::filesystem::path& to) {
  namespace fs = std::filesystem;
  std::error_code error;
  for (fs::recursive_directory_iterator it(from, error), end; !error && it != end;
       it.increment(error)) {
    const fs::path target = to / fs::relative(it->path(), from);
    if (it->is_directory(error)) {
      fs::create_directories(target, error);
    } else if (it->path().filename().string().find(".tmp.") == std::string::npos) {
      fs::copy_file(it->path(), target, error);
    }
    error.clear();
  }
}

TEST(SweepTest, ACoordinatorRestoredFromABackupTakenMidSweepFinishesItWithTheSameReport) {
  const std::string spec = WriteSpec(EightRunSweepSpec("small", 1536, 512));
  ClusterProcesses original(kLease);
  StartCoordinatorLearnerAndActors(original);
  const RunResult queued = DcsAt({"submit", spec}, original.coordinator_address());
  ASSERT_EQ(queued.exit_code, 0) << queued.output;
  WaitForCompleted(original, "sweep-1", 2);

  // Backed up mid-sweep; restored as docs/deploy.md's Backups says: the backup as the new
  // coordinator's store, the runs' files copied after it (here once the sweep ended: runs the
  // backup holds as running then have the checkpoints of their ends, which a learner resuming
  // them must finish at once).
  const std::string backup = original.dir() + "/backup.db";
  const RunResult backed_up =
      DcsAt({"backup", "--out", backup}, original.coordinator_address());
  ASSERT_EQ(backed_up.exit_code, 0) << backed_up.output << "; logs in " << original.dir();
  EXPECT_THAT(backed_up.output, HasSubstr(backup + ": "));
  EXPECT_THAT(backed_up.output, HasSubstr(" bytes, 8 runs, 1 sweeps, 0 studies"));
  ClusterProcesses restored(kLease);
  std::filesystem::create_directories(restored.data_dir());
  std::filesystem::copy_file(backup, restored.data_dir() + "/coordinator.db");

  const RunResult finished =
      DcsAt({"watch", "sweep-1"}, original.coordinator_address(), absl::Minutes(5));
  ASSERT_EQ(finished.exit_code, 0) << finished.output << "; logs in " << original.dir();
  CopyRunFiles(original.data_dir() + "/runs", restored.data_dir() + "/runs");
  const std::string reports = SweepReports(original, "sweep-1");
  for (const char* worker : {"learner", "actor-1", "actor-2"}) original.Kill(worker);

  restored.StartCoordinator();
  absl::StatusOr<v1::GetSweepResponse> as_backed_up =
      services::cli::GetSweep(restored.coordinator_address(), "sweep-1", kTimeout);
  ASSERT_TRUE(as_backed_up.ok()) << as_backed_up.status();
  EXPECT_GE(as_backed_up->sweep().completed(), 2);
  EXPECT_LT(as_backed_up->sweep().completed(), 8) << "the backup was not taken mid-sweep";
  restored.StartLearner("learner");
  restored.StartActor("actor-1", 4);
  restored.StartActor("actor-2", 4);
  const RunResult watched =
      DcsAt({"watch", "sweep-1"}, restored.coordinator_address(), absl::Minutes(5));
  ASSERT_EQ(watched.exit_code, 0) << watched.output << "; logs in " << restored.dir();
  EXPECT_EQ(SweepReports(restored, "sweep-1"), reports);
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
