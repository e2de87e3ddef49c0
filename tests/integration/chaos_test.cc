// Copyright 2026 The DCS Authors.
//
// Chaos under a running sweep (spec/operations.md §7.2): while a sweep runs on a cluster of
// real processes on loopback, a killer SIGKILLs a random process (the coordinator, the learner
// or an actor) every 1 to 2.5 seconds and restarts it at once, from a seeded schedule. The
// sweep must complete with the same report, in every format, as an undisturbed run of the same
// sweep: no run or evaluation lost or counted twice, and every run bit for bit the same.

#include <random>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/run_client.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

using ::testing::HasSubstr;

constexpr absl::Duration kLease = absl::Seconds(1);

// Two conditions in two modes, two seeds: 8 runs, each evaluated and checkpointed 4 times,
// long enough for the killer to strike while they run.
constexpr char kSpec[] = R"(name: chaos
seeds: 2
observe: [none, live]
env: cartpole
total_timesteps: 131072
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
evaluation: {freq: 32768, episodes: 2, contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0]}}
ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}
conditions:
  - name: static
  - schedule: {family: sinusoidal, period: 40}
    grid: {schedule.amplitude_frac: [0.5]}
)";

// The sweep's state as `dcs` sees it, or UNSPECIFIED while the coordinator is down.
v1::SweepState SweepState(const ClusterProcesses& cluster) {
  absl::StatusOr<v1::GetSweepResponse> sweep =
      services::cli::GetSweep(cluster.coordinator_address(), "sweep-1", absl::Seconds(2));
  return sweep.ok() ? sweep->sweep().state() : v1::SWEEP_STATE_UNSPECIFIED;
}

TEST(ChaosTest, ASweepUnderRandomKillsReportsAsAnUndisturbedOne) {
  const std::string spec = absl::StrCat(testing::MakeTempDir(), "/chaos.yaml");
  ASSERT_TRUE(WriteFileAtomically(spec, kSpec).ok());

  ClusterProcesses calm(kLease);
  StartCoordinatorLearnerAndActors(calm);
  const RunResult watched =
      DcsAt({"submit", spec, "--watch"}, calm.coordinator_address(), absl::Minutes(5));
  ASSERT_EQ(watched.exit_code, 0) << watched.output << "; logs in " << calm.dir();
  ASSERT_THAT(watched.output, HasSubstr("sweep-1 chaos: completed, 8/8 runs done"));
  const std::string undisturbed = SweepReports(calm, "sweep-1");

  ClusterProcesses chaos(kLease);
  StartCoordinatorLearnerAndActors(chaos);
  const RunResult submitted = DcsAt({"submit", spec}, chaos.coordinator_address());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  std::mt19937 random(20261125);  // the kill schedule is the same at every run of the test
  std::uniform_int_distribution<int> pause_ms(1000, 2500);
  std::vector<std::string> killed;
  const absl::Time deadline = absl::Now() + absl::Minutes(5);
  while (SweepState(chaos) != v1::SWEEP_STATE_COMPLETED) {
    ASSERT_LT(absl::Now(), deadline) << "killed " << absl::StrJoin(killed, ", ")
                                     << "; logs in " << chaos.dir();
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

  const absl::StatusOr<v1::GetSweepResponse> sweep =
      services::cli::GetSweep(chaos.coordinator_address(), "sweep-1", absl::Seconds(5));
  ASSERT_TRUE(sweep.ok()) << sweep.status();
  EXPECT_EQ(sweep->sweep().completed(), 8);
  EXPECT_EQ(sweep->sweep().failed(), 0);
  EXPECT_EQ(SweepReports(chaos, "sweep-1"), undisturbed)
      << "killed " << absl::StrJoin(killed, ", ") << "; logs in " << chaos.dir();
}

}  // namespace
}  // namespace dcs::integration
