// Copyright 2026 The DCS Authors.
//
// Faults under a running sweep, with real processes on loopback. Each
// faulty run of the same sweep must end with the report, in every format, of an undisturbed
// run: no run or evaluation lost or counted twice, every run bit for bit the same.
// - Chaos: a killer SIGKILLs a random process (the coordinator, the learner or an actor) every
//   1 to 2.5 seconds and restarts it at once, from a seeded schedule, up to 8 times.
// - A full disk: the coordinator's data directory is a 3 MiB tmpfs, which the sweep's
//   checkpoints fill. The coordinator stays up and says which file could not be written;
//   workers wait rather than fail runs; once the disk is made larger the sweep completes.
// - A damaged checkpoint: the newest checkpoint of a run whose learner died has a bit flipped;
//   the run resumes from the one before it.
// - A corrupt store: the coordinator refuses to start, naming the file.

#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "absl/cleanup/cleanup.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/strip.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/cluster_client.h"
#include "services/cli/run_client.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {
namespace {

using ::testing::HasSubstr;

constexpr absl::Duration kLease = absl::Seconds(1);

// The sweep's state as `dcs` sees it, or UNSPECIFIED while the coordinator is down.
v1::SweepState SweepState(const ClusterProcesses& cluster) {
  absl::StatusOr<v1::GetSweepResponse> sweep =
      services::cli::GetSweep(cluster.coordinator_address(), "sweep-1", absl::Seconds(2));
  return sweep.ok() ? sweep->sweep().state() : v1::SWEEP_STATE_UNSPECIFIED;
}

// The sweep's spec, and its report as an undisturbed cluster gives it: computed once, by the
// first test (in SetUp, not SetUpTestSuite: a failed assertion there marks the tests skipped,
// which ctest, matching gtest's "[  SKIPPED ]", does not count as a failure).
class FaultsTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_NO_FATAL_FAILURE(RunUndisturbedOnce()); }

  static void RunUndisturbedOnce() {
    if (undisturbed_ != nullptr) return;
    spec_ = new std::string(absl::StrCat(testing::MakeTempDir(), "/faults.yaml"));
    // 8 runs, each evaluated and checkpointed 4 times, long enough for the faults to strike
    // while they run.
    ASSERT_TRUE(WriteFileAtomically(*spec_, EightRunSweepSpec("chaos", 131072, 32768)).ok());
    ClusterProcesses calm(kLease);
    StartCoordinatorLearnerAndActors(calm);
    const RunResult watched =
        DcsAt({"submit", *spec_, "--watch"}, calm.coordinator_address(), absl::Minutes(5));
    ASSERT_EQ(watched.exit_code, 0) << watched.output << "; logs in " << calm.dir();
    ASSERT_THAT(watched.output, HasSubstr("sweep-1 chaos: completed, 8/8 runs done"));
    undisturbed_ = new std::string(SweepReports(calm, "sweep-1"));
  }

  // Waits for the sweep to complete; then expects it whole and its report the undisturbed one.
  static void ExpectTheUndisturbedReport(const ClusterProcesses& cluster,
                                         const std::string& faults) {
    const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(5));
    while (SweepState(cluster) != v1::SWEEP_STATE_COMPLETED) {
      ASSERT_LT(absl::Now(), deadline) << faults << "; logs in " << cluster.dir();
      absl::SleepFor(absl::Milliseconds(200));
    }
    const absl::StatusOr<v1::GetSweepResponse> sweep =
        services::cli::GetSweep(cluster.coordinator_address(), "sweep-1", absl::Seconds(5));
    ASSERT_TRUE(sweep.ok()) << sweep.status();
    EXPECT_EQ(sweep->sweep().completed(), 8);
    EXPECT_EQ(sweep->sweep().failed(), 0);
    EXPECT_EQ(SweepReports(cluster, "sweep-1"), *undisturbed_)
        << faults << "; logs in " << cluster.dir();
  }

  static std::string* spec_;
  static std::string* undisturbed_;
};

std::string* FaultsTest::spec_ = nullptr;
std::string* FaultsTest::undisturbed_ = nullptr;

TEST_F(FaultsTest, ASweepUnderRandomKillsReportsAsAnUndisturbedOne) {
  ClusterProcesses chaos(kLease);
  StartCoordinatorLearnerAndActors(chaos);
  const RunResult submitted = DcsAt({"submit", *spec_}, chaos.coordinator_address());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  std::mt19937 random(20261125);  // the kill schedule is the same at every run of the test
  std::uniform_int_distribution<int> pause_ms(1000, 2500);
  std::vector<std::string> killed;
  // Bounded: a learner killed more often than its runs checkpoint (on a loaded machine) would
  // keep them from ever finishing.
  constexpr size_t kMaxKills = 8;
  while (killed.size() < kMaxKills && SweepState(chaos) != v1::SWEEP_STATE_COMPLETED) {
    absl::SleepFor(absl::Milliseconds(pause_ms(random)));
    const std::vector<std::string> running = chaos.Running();
    const std::string& victim = running[random() % running.size()];
    killed.push_back(victim);
    chaos.Kill(victim);
    chaos.Restart(victim);
  }
  std::cerr << "chaos: " << killed.size() << " kills: " << absl::StrJoin(killed, ", ") << "\n";
  // A sweep that ended before the killer struck would prove nothing.
  EXPECT_GE(killed.size(), 3u) << "the sweep ended before the killer struck";
  ExpectTheUndisturbedReport(chaos, absl::StrCat("killed ", absl::StrJoin(killed, ", ")));
}

TEST_F(FaultsTest, AFullDiskStallsTheSweepWithClearErrorsAndLosesNothing) {
  std::string mount_point;  // unmounted after the cluster's processes are gone
  absl::Cleanup unmount = [&mount_point] {
    if (!mount_point.empty()) ::umount2(mount_point.c_str(), MNT_DETACH);
  };
  ClusterProcesses cluster(kLease);
  mount_point = absl::StrCat(cluster.dir(), "/data");  // the coordinator's data directory
  std::filesystem::create_directories(mount_point);
  if (::mount("dcs-test", mount_point.c_str(), "tmpfs", 0, "size=3m") != 0) {
    mount_point.clear();
    GTEST_SKIP() << "mounting a tmpfs needs root (CAP_SYS_ADMIN): " << std::strerror(errno);
  }
  StartCoordinatorLearnerAndActors(cluster);
  const RunResult submitted = DcsAt({"submit", *spec_}, cluster.coordinator_address());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;

  // The checkpoints fill the disk: the coordinator says so, naming the file, and stays up.
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(2));
  while (!absl::StrContains(cluster.Log("coordinator"), "the disk is full")) {
    ASSERT_LT(absl::Now(), deadline) << "the disk never filled; logs in " << cluster.dir();
    absl::SleepFor(absl::Milliseconds(200));
  }
  EXPECT_THAT(cluster.Log("coordinator"),
              HasSubstr(absl::StrCat(mount_point, "/coordinator.db: the disk is full")));
  absl::SleepFor(absl::Seconds(3));  // full for a while: leases come due, workers retry
  absl::StatusOr<bool> serving =
      services::cli::IsServing(cluster.coordinator_address(), "", absl::Seconds(5));
  EXPECT_TRUE(serving.ok() && *serving) << serving.status();
  const absl::StatusOr<v1::GetSweepResponse> stalled =
      services::cli::GetSweep(cluster.coordinator_address(), "sweep-1", absl::Seconds(5));
  ASSERT_TRUE(stalled.ok()) << stalled.status();
  EXPECT_EQ(stalled->sweep().failed(), 0) << "a run failed for the coordinator's full disk";
  EXPECT_LT(stalled->sweep().completed(), 8) << "the disk filled too late to matter";

  // Room again: the sweep goes on to the undisturbed report.
  ASSERT_EQ(::mount("dcs-test", mount_point.c_str(), "tmpfs", MS_REMOUNT, "size=256m"), 0)
      << std::strerror(errno);
  ExpectTheUndisturbedReport(cluster, "the disk was full for a while");
}

TEST_F(FaultsTest, ABitFlippedCheckpointFallsBackToThePreviousOne) {
  ClusterProcesses cluster(kLease);
  StartCoordinatorLearnerAndActors(cluster);
  const RunResult submitted = DcsAt({"submit", *spec_}, cluster.coordinator_address());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;

  // Once run-1 has two checkpoints, its learner dies and the newer one is damaged on the
  // coordinator's disk: one bit of its learner.bin flipped.
  const std::filesystem::path checkpoints =
      std::filesystem::path(cluster.dir()) / "data/runs/run-1/checkpoints";
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(2));
  std::string latest;
  while (true) {
    ASSERT_LT(absl::Now(), deadline)
        << "run-1 never had two checkpoints; logs in " << cluster.dir();
    int stored = 0;
    if (std::filesystem::exists(checkpoints)) {
      for (const auto& entry : std::filesystem::directory_iterator(checkpoints)) {
        stored += entry.is_directory();
      }
    }
    if (stored >= 2) break;
    absl::SleepFor(absl::Milliseconds(20));
  }
  cluster.Kill("learner");
  latest = std::string(
      absl::StripAsciiWhitespace(ReadFile((checkpoints / "latest").string()).value_or("")));
  const std::string damaged = (checkpoints / latest / "learner.bin").string();
  absl::StatusOr<std::string> bytes = ReadFile(damaged);
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  (*bytes)[bytes->size() / 2] ^= 0x10;
  ASSERT_TRUE(WriteFileAtomically(damaged, *bytes).ok());
  cluster.Restart("learner");

  ExpectTheUndisturbedReport(cluster, absl::StrCat("checkpoint ", latest, " of run-1 damaged"));
}

TEST(CorruptStoreTest, TheCoordinatorRefusesToStartNamingTheFile) {
  const std::string data_dir = testing::MakeTempDir();
  const std::string store = absl::StrCat(data_dir, "/coordinator.db");
  ASSERT_TRUE(WriteFileAtomically(store, std::string(8192, 'x')).ok());
  const RunResult started =
      RunProgram(BinaryPath("dcs-coordinator"),
                 {"--listen=127.0.0.1:0", "--metrics-listen=127.0.0.1:0", "--data-dir", data_dir},
                 absl::Seconds(30));
  EXPECT_NE(started.exit_code, 0) << started.output;
  EXPECT_NE(started.exit_code, -1) << "it did not stop on its own";
  EXPECT_THAT(started.output, HasSubstr(absl::StrCat(store, " is corrupt")));
}

}  // namespace
}  // namespace dcs::integration
