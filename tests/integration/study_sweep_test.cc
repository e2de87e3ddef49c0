// Copyright 2026 The DCS Authors.
//
// Study sweeps end to end, with real processes on loopback and the `dcs` client: a TPE search
// over a two-stage curriculum submitted with `dcs submit` asks, trains, tells and retrains on its
// own, and `dcs report` and `dcs plot` show it; a search whose coordinator is killed (SIGKILL)
// twice mid-way and restarted on its data directory finishes with the same trials, values and runs
// as an undisturbed one: no trial lost, none asked or trained twice.

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
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

// Six trials of two seeds, one at a time (so each trial's values follow from the ones before,
// whatever the timing), TPE modelling from the third; the two best retrained with one new seed.
constexpr char kSpec[] = R"(name: curriculum
seeds: 2
observe: [live]
env: cartpole
total_timesteps: 1024
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
evaluation: {freq: 100000, episodes: 2, contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0]}}
ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}
conditions:
  - name: search
    stages:
      - {steps: 512, schedule: {family: constant}}
      - {steps: 512, schedule: {family: constant}}
study:
  trials: 6
  seed: 5
  tpe: {startup_trials: 2}
  retrain: {top_k: 2, seeds: 1}
  space:
    parameters:
      - {name: "stages[0].schedule.family", type: categorical, choices: [constant, sinusoidal]}
      - {name: "stages[0].schedule.amplitude_frac", type: float, low: 0.2, high: 1,
         when: {"stages[0].schedule.family": sinusoidal}}
      - {name: "stages[1].schedule.family", type: categorical,
         choices: [constant, cosine_annealing]}
      - {name: "stages[1].schedule.neighborhood_radius_frac", type: float, low: 0.2, high: 1,
         when: {"stages[1].schedule.family": cosine_annealing}}
      - {name: "stages[1].schedule.T_0", type: int, low: 20, high: 200, log: true,
         when: {"stages[1].schedule.family": cosine_annealing}}
)";

// The study's trials as `dcs study trials -o json` prints them, one JSON line each.
std::vector<std::string> StudyTrials(const ClusterProcesses& cluster) {
  const RunResult trials =
      DcsAt({"study", "trials", "study-1", "-o", "json"}, cluster.coordinator_address());
  EXPECT_EQ(trials.exit_code, 0) << trials.output;
  return absl::StrSplit(absl::StripTrailingAsciiWhitespace(trials.output), '\n', absl::SkipEmpty());
}

// Waits until the study has at least `complete` complete trials.
void WaitForTrials(const ClusterProcesses& cluster, int complete) {
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(4));
  while (absl::Now() < deadline) {
    const RunResult trials =
        DcsAt({"study", "trials", "study-1", "-o", "json"}, cluster.coordinator_address());
    int done = 0;
    for (absl::string_view line : absl::StrSplit(trials.output, '\n', absl::SkipEmpty())) {
      google::protobuf::Struct trial;  // none while the coordinator is down: not JSON
      if (!google::protobuf::util::JsonStringToMessage(std::string(line), &trial).ok()) continue;
      const auto state = trial.fields().find("state");
      done += state != trial.fields().end() && state->second.string_value() == "complete" ? 1 : 0;
    }
    if (done >= complete) return;
    absl::SleepFor(absl::Milliseconds(200));
  }
  FAIL() << "the study did not complete " << complete << " trials; logs in " << cluster.dir();
}

// Each (trial, seed) of the sweep's runs, with how many runs train it.
std::map<std::pair<int, uint64_t>, int> RunsPerTrialAndSeed(const v1::GetSweepResponse& sweep) {
  std::map<std::pair<int, uint64_t>, int> runs;
  for (const v1::Run& run : sweep.runs()) ++runs[{run.trial(), run.seed()}];
  return runs;
}

TEST(StudySweepTest, ASearchSurvivesItsCoordinatorsDeathWithNoTrialLostOrRunTwice) {
  const std::string spec = testing::MakeTempDir() + "/curriculum.yaml";
  ASSERT_TRUE(WriteFileAtomically(spec, kSpec).ok());

  // Undisturbed: submitted, watched to its end.
  ClusterProcesses calm(kLease);
  StartCoordinatorLearnerAndActors(calm);
  const RunResult submitted =
      DcsAt({"submit", spec, "--watch"}, calm.coordinator_address(), absl::Minutes(5));
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output << "; logs in " << calm.dir();
  EXPECT_THAT(submitted.output, HasSubstr("a search: study-1 asks for its trials"));
  const std::vector<std::string> undisturbed = StudyTrials(calm);
  ASSERT_EQ(undisturbed.size(), 6u);
  for (const std::string& trial : undisturbed) EXPECT_THAT(trial, HasSubstr("\"complete\""));
  absl::StatusOr<v1::GetSweepResponse> calm_sweep =
      services::cli::GetSweep(calm.coordinator_address(), "sweep-1", kTimeout);
  ASSERT_TRUE(calm_sweep.ok()) << calm_sweep.status();
  EXPECT_EQ(calm_sweep->sweep().state(), v1::SWEEP_STATE_COMPLETED);
  EXPECT_FALSE(calm_sweep->sweep().open());
  ASSERT_EQ(calm_sweep->sweep().trials_size(), 8);  // 6 searched, 2 retrained
  EXPECT_TRUE(calm_sweep->sweep().trials(6).retrain());
  EXPECT_EQ(calm_sweep->runs_size(), 6 * 2 + 2 * 1);
  std::set<uint64_t> retrain_seeds;
  for (const v1::Run& run : calm_sweep->runs()) {
    if (run.trial() >= 6) retrain_seeds.insert(run.seed());
  }
  EXPECT_EQ(retrain_seeds, std::set<uint64_t>{2});  // new: after the search's 0 and 1

  // Its report ranks the trials and compares the retrain; its figures show in a browser.
  const RunResult report = DcsAt({"report", "sweep-1"}, calm.coordinator_address());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  EXPECT_THAT(report.output, HasSubstr("trials ranked by best_anytime over 2 seeds"));
  EXPECT_THAT(report.output, HasSubstr("Stage modes of the best 6 trials"));
  EXPECT_THAT(report.output, HasSubstr("Retrain: 2 trials with 1 new seeds each"));
  const std::string figures = calm.dir() + "/figures";
  const RunResult plotted =
      DcsAt({"plot", "sweep-1", "--out", figures}, calm.coordinator_address());
  ASSERT_EQ(plotted.exit_code, 0) << plotted.output;
  const std::vector<std::string> images = LoadedImages(figures + "/index.html");
  EXPECT_EQ(images.size(), 3u);  // the history, the stage modes, the rank shift
  for (const std::string& image : images) EXPECT_THAT(image, HasSubstr(" loaded ")) << image;

  // The coordinator killed after two trials and again after four, restarted each time.
  ClusterProcesses faulty(kLease);
  StartCoordinatorLearnerAndActors(faulty);
  ASSERT_EQ(DcsAt({"submit", spec}, faulty.coordinator_address()).exit_code, 0);
  for (int complete : {2, 4}) {
    WaitForTrials(faulty, complete);
    faulty.Kill("coordinator");
    absl::SleepFor(2 * kLease);
    faulty.StartCoordinator();
  }
  const RunResult watched =
      DcsAt({"watch", "sweep-1"}, faulty.coordinator_address(), absl::Minutes(5));
  ASSERT_EQ(watched.exit_code, 0) << watched.output << "; logs in " << faulty.dir();
  EXPECT_EQ(StudyTrials(faulty), undisturbed);
  absl::StatusOr<v1::GetSweepResponse> faulty_sweep =
      services::cli::GetSweep(faulty.coordinator_address(), "sweep-1", kTimeout);
  ASSERT_TRUE(faulty_sweep.ok()) << faulty_sweep.status();
  EXPECT_EQ(faulty_sweep->sweep().trials_size(), 8);
  EXPECT_EQ(RunsPerTrialAndSeed(*faulty_sweep), RunsPerTrialAndSeed(*calm_sweep));
  for (const auto& [trial_and_seed, runs] : RunsPerTrialAndSeed(*faulty_sweep)) {
    EXPECT_EQ(runs, 1) << "trial " << trial_and_seed.first << " seed " << trial_and_seed.second;
  }

  // Its study is the coordinator's to ask and tell.
  const RunResult ask = DcsAt({"study", "ask", "study-1"}, faulty.coordinator_address());
  EXPECT_NE(ask.exit_code, 0);
  EXPECT_THAT(ask.output, HasSubstr("study-1 is driven by sweep-1"));
}

}  // namespace
}  // namespace dcs::integration
