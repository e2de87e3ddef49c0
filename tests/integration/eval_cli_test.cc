// Copyright 2026 The DCS Authors.
//
// `dcs eval` as a researcher runs it on a trained run: a grid of two features gives a table, a
// JSON of every cell and episode, and a heatmap that loads in headless Chromium; a run on a
// cluster is evaluated by its id, in this process or by the cluster's actors (--on-actors), with
// the same returns, and a sweep's condition as its runs averaged; every bad input is one error
// line that writes nothing.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <google/protobuf/util/json_util.h>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "dcs/v1/evaluation.pb.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/exit_codes.h"
#include "tests/integration/browser.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/net.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

namespace fs = std::filesystem;
using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::SizeIs;

RunResult Dcs(const std::vector<std::string>& args) { return RunProgram(BinaryPath("dcs"), args); }

// A CartPole run of 1,536 steps in 256-step rollouts, evaluated (and so checkpointed) every
// 512.
constexpr char kTinyRun[] = R"(
env: cartpole
seed: 3
total_timesteps: 1536
feature: length
training_range: [0.35, 0.75]
pool: {values: [0.35, 0.55, 0.75]}
evaluation: {freq: 512, episodes: 2, contexts: {id: [0.5], ood_high: [1.0]}}
ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}
)";

class EvalCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(testing::MakeTempDir());
    ASSERT_TRUE(WriteFileAtomically(*dir_ + "/tiny.yaml", kTinyRun).ok());
    const RunResult train = Dcs({"train", "--config", *dir_ + "/tiny.yaml", "--out", Run(),
                                 "--keep", "10"});
    ASSERT_EQ(train.exit_code, 0) << train.output;
  }
  static void TearDownTestSuite() { delete dir_; }

  static std::string Run() { return *dir_ + "/run"; }
  // A path under the test's directory that nothing has written.
  static std::string Fresh(const std::string& name) { return *dir_ + "/" + name; }

  // `dcs eval ARGS...`, which must fail with one error line naming `message`, exit `code`,
  // writing nothing into `out`.
  static void ExpectRefused(std::vector<std::string> args, const std::string& message,
                            int code) {
    const std::string out = Fresh(absl::StrCat("refused-", refusals_++));
    args.insert(args.begin(), "eval");
    args.insert(args.end(), {"--out", out});
    const RunResult eval = Dcs(args);
    EXPECT_EQ(eval.exit_code, code) << eval.output;
    EXPECT_THAT(Lines(eval.output), SizeIs(1)) << eval.output;
    EXPECT_THAT(eval.output, HasSubstr(message));
    EXPECT_FALSE(fs::exists(out)) << out;
  }

  // The tiny run trained on `cluster` (its directory `name`): its run id, empty on a failure.
  static std::string TrainOnCluster(const ClusterProcesses& cluster, const std::string& name) {
    const RunResult train = DcsAt(
        {"train", "--cluster", "--config", *dir_ + "/tiny.yaml", "--out", Fresh(name)},
        cluster.coordinator_address(), absl::Minutes(2));
    EXPECT_EQ(train.exit_code, 0) << train.output;
    std::smatch submitted;
    if (!std::regex_search(train.output, submitted, std::regex("submitted (\\S+) to"))) {
      ADD_FAILURE() << "no run id in: " << train.output;
      return "";
    }
    return submitted[1];
  }

  static std::string* dir_;
  static int refusals_;
};

std::string* EvalCliTest::dir_ = nullptr;
int EvalCliTest::refusals_ = 0;

TEST_F(EvalCliTest, TwoFeaturesGiveATableAndAHeatmapThatLoadsInABrowser) {
  const std::string out = Fresh("heatmap");
  const RunResult eval = Dcs({"eval", Run(), "--grid", "length=0.2:1.6:8", "--grid",
                              "gravity=4:16:4", "--episodes", "3", "--out", out, "--format",
                              "svg"});
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  EXPECT_THAT(eval.output, ContainsRegex("RUN +STEP +length +gravity +MEAN +STD"));
  EXPECT_THAT(eval.output, ContainsRegex("run +1536 +0.2 +4 "));
  EXPECT_THAT(eval.output, ContainsRegex("run +1536 +1.6 +16 "));
  // The cells as CSV: a header and 32 cells.
  absl::StatusOr<std::string> csv = ReadFile(out + "/cells.csv");
  ASSERT_TRUE(csv.ok()) << csv.status();
  EXPECT_THAT(Lines(*csv), SizeIs(33));
  // The heatmap, at its own size in a page, then as a person sees it: the viridis ends of the
  // colour scale and the training contexts' vermillion points.
  ASSERT_TRUE(WriteFileAtomically(out + "/index.html",
                                  "<html><body><img src=\"generalization.svg\"></body></html>")
                  .ok());
  const std::vector<std::string> images = LoadedImages(out + "/index.html");
  ASSERT_THAT(images, SizeIs(1));
  EXPECT_THAT(images[0], ContainsRegex("^generalization.svg loaded [5-9][0-9][0-9]x[4-9]"));
  const Screenshot shot = TakeScreenshot(out + "/index.html", out + "/index.png", 700, 600);
  ASSERT_EQ(shot.width, 700);
  int purple = 0, yellow = 0, vermillion = 0;
  std::set<int> colours;
  for (size_t i = 0; i + 2 < shot.rgb.size(); i += 3) {
    const int r = shot.rgb[i], g = shot.rgb[i + 1], b = shot.rgb[i + 2];
    const auto near = [&](int R, int G, int B) {
      return std::abs(r - R) < 24 && std::abs(g - G) < 24 && std::abs(b - B) < 24;
    };
    purple += near(0x44, 0x01, 0x54);
    yellow += near(0xfd, 0xe7, 0x25);
    vermillion += near(0xd5, 0x5e, 0x00);
    colours.insert((r << 16) | (g << 8) | b);
  }
  EXPECT_GT(purple, 100);  // the colour bar's low end, and the worst cells
  EXPECT_GT(yellow, 100);  // its high end
  EXPECT_GT(vermillion, 50);
  EXPECT_GT(colours.size(), 50u);
}

TEST_F(EvalCliTest, JsonHoldsEveryCellAndEpisodeOfEveryRun) {
  const RunResult eval = Dcs({"eval", Run(), Run(), "--grid", "length=0.3:1.2:4",
                              "--episodes", "5", "--seed", "9", "-o", "json"});
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  v1::GeneralizationGrid grid;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(eval.output, &grid).ok())
      << eval.output;
  EXPECT_EQ(grid.env(), "cartpole");
  ASSERT_THAT(grid.axes(), SizeIs(1));
  EXPECT_EQ(grid.axes(0).feature(), "length");
  EXPECT_EQ(grid.axes(0).count(), 4);
  EXPECT_EQ(grid.episodes(), 5);
  ASSERT_THAT(grid.policies(), SizeIs(2));
  EXPECT_EQ(grid.policies(0).name(), Run());
  ASSERT_THAT(grid.policies(0).runs(), SizeIs(1));
  EXPECT_EQ(grid.policies(0).runs(0).step(), 1536);
  EXPECT_EQ(grid.policies(0).runs(0).checkpoint(), "000000001536");
  ASSERT_THAT(grid.policies(0).cells(), SizeIs(4));
  for (int c = 0; c < 4; ++c) {
    const v1::GridCell& cell = grid.policies(0).cells(c);
    EXPECT_NEAR(cell.context(0), 0.3 + 0.3 * c, 1e-12);
    EXPECT_THAT(cell.returns(), SizeIs(5));
    // The same policy and episodes give the same returns.
    EXPECT_EQ(cell.SerializeAsString(), grid.policies(1).cells(c).SerializeAsString());
  }
}

TEST_F(EvalCliTest, AnOlderCheckpointOrTheBestIsEvaluated) {
  const RunResult older = Dcs({"eval", Run(), "--checkpoint", "512", "--grid",
                               "length=0.5:0.5:1", "--episodes", "2"});
  ASSERT_EQ(older.exit_code, 0) << older.output;
  EXPECT_THAT(older.output, ContainsRegex("run +512 +0.5 "));
  const RunResult best = Dcs({"eval", Run(), "--checkpoint", "best", "--grid",
                              "length=0.5:0.5:1", "--episodes", "2"});
  ASSERT_EQ(best.exit_code, 0) << best.output;
  EXPECT_THAT(best.output, ContainsRegex("run +(512|1024|1536) +0.5 "));
}

TEST_F(EvalCliTest, AnUnknownFeatureGetsTrainsMessage) {
  // What `dcs train` says of the same feature in a config.
  const std::string config = Fresh("typo.yaml");
  ASSERT_TRUE(WriteFileAtomically(config, std::regex_replace(kTinyRun, std::regex("feature: "
                                                                                  "length"),
                                                             "feature: lenght"))
                  .ok());
  const RunResult train = Dcs({"train", "--config", config, "--out", Fresh("typo-run")});
  const std::string message =
      "unknown context feature 'lenght' (known: gravity, masscart, masspole, length, "
      "force_mag, tau, initial_state_lower, initial_state_upper)";
  ASSERT_THAT(train.output, HasSubstr(message));
  ExpectRefused({Run(), "--grid", "lenght=0.1:1:3"}, message, services::kExitDataError);
}

TEST_F(EvalCliTest, AValueOutsideThePhysicalRangeIsRefused) {
  ExpectRefused({Run(), "--grid", "length=-1:1:3"}, "context feature 'length' must be in [",
                services::kExitDataError);
}

TEST_F(EvalCliTest, ARunThatDoesNotExistIsRefused) {
  ExpectRefused({Fresh("no/such/run"), "--grid", "length=0.1:1:3"}, "no run directory ",
                services::kExitNoInput);
  fs::create_directories(Fresh("not-a-run"));
  ExpectRefused({Fresh("not-a-run"), "--grid", "length=0.1:1:3"},
                "no run in " + Fresh("not-a-run"), services::kExitNoInput);
  ExpectRefused({Run(), "--checkpoint", "100", "--grid", "length=0.1:1:3"},
                "no checkpoint at step 100 in " + Run() + " (kept: 512, 1024, 1536)",
                services::kExitNoInput);
}

TEST_F(EvalCliTest, ACorruptCheckpointIsDataLossNamingTheFile) {
  const std::string copy = Fresh("corrupt-run");
  fs::copy(Run(), copy, fs::copy_options::recursive);
  const std::string learner = copy + "/checkpoints/000000001536/learner.bin";
  {
    std::fstream file(learner, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(100);
    file.put('\x7f');
  }
  ExpectRefused({copy, "--grid", "length=0.1:1:3"},
                "DATA_LOSS: " + learner + " does not match the checkpoint's MANIFEST",
                services::kExitFailure);
}

TEST_F(EvalCliTest, AGridTooLargeStatesItsCountAndAsksForYes) {
  ExpectRefused({Run(), "--grid", "length=0.1:1:100", "--grid", "gravity=5:15:100",
                 "--episodes", "10"},
                "the grid is 100000 episodes (10000 cells x 10 episodes x 1 runs), more than "
                "50000: pass --yes to run it",
                services::kExitFailure);
}

TEST_F(EvalCliTest, ARunOnTheClusterIsEvaluatedByItsId) {
  ClusterProcesses cluster(absl::Seconds(5));
  StartCoordinatorLearnerAndActors(cluster);
  const std::string run_id = TrainOnCluster(cluster, "cluster-run");
  ASSERT_FALSE(run_id.empty());
  const RunResult eval = DcsAt({"eval", run_id, "--grid", "length=0.5:1:2", "--episodes", "2"},
                               cluster.coordinator_address());
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  EXPECT_THAT(eval.output, ContainsRegex(run_id + " +1536 +0.5 "));
  // Bit for bit the run as trained in one process: the same returns.
  const RunResult local =
      Dcs({"eval", Run(), "--grid", "length=0.5:1:2", "--episodes", "2"});
  ASSERT_EQ(local.exit_code, 0) << local.output;
  EXPECT_EQ(Lines(eval.output).back().substr(run_id.size()),
            Lines(local.output).back().substr(Run().size()));

  const RunResult missing = DcsAt({"eval", "run-missing", "--grid", "length=0.5:1:2"},
                                  cluster.coordinator_address());
  EXPECT_EQ(missing.exit_code, services::kExitNoInput) << missing.output;
  EXPECT_THAT(Lines(missing.output), SizeIs(1)) << missing.output;
  EXPECT_THAT(missing.output, HasSubstr("no run run-missing: neither a directory nor a run on "
                                        "the cluster at "));
}

TEST_F(EvalCliTest, ASweepConditionIsItsRunsAveraged) {
  ClusterProcesses cluster(absl::Seconds(5));
  StartCoordinatorLearnerAndActors(cluster);
  const std::string spec = Fresh("sweep.yaml");
  ASSERT_TRUE(WriteFileAtomically(spec, EightRunSweepSpec("small", 512, 512)).ok());
  const RunResult submitted =
      DcsAt({"submit", spec, "--watch"}, cluster.coordinator_address(), absl::Minutes(3));
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;

  // Both modes of the condition: which one is asked.
  const RunResult ambiguous = DcsAt({"eval", "sweep-1:static", "--grid", "length=0.3:1.2:3"},
                                    cluster.coordinator_address());
  EXPECT_EQ(ambiguous.exit_code, services::kExitDataError) << ambiguous.output;
  EXPECT_THAT(ambiguous.output,
              HasSubstr("sweep-1:static is in several modes (choose one of: "
                        "sweep-1:static:none, sweep-1:static:live, "));
  const RunResult unknown = DcsAt({"eval", "sweep-1:statik:none", "--grid", "length=0.3:1.2:3"},
                                  cluster.coordinator_address());
  EXPECT_THAT(unknown.output, HasSubstr("sweep-1:statik:none is no condition of the sweep"));

  const RunResult condition =
      DcsAt({"eval", "sweep-1:static:none", "--grid", "length=0.3:1.2:3", "--episodes", "4",
             "-o", "json"},
            cluster.coordinator_address());
  ASSERT_EQ(condition.exit_code, 0) << condition.output;
  v1::GeneralizationGrid grid;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(condition.output, &grid).ok())
      << condition.output;
  ASSERT_THAT(grid.policies(), SizeIs(1));
  const v1::PolicyGrid& policy = grid.policies(0);
  ASSERT_THAT(policy.runs(), SizeIs(2));  // its two seeds
  ASSERT_THAT(policy.cells(), SizeIs(3));
  bool seeds_differ = false;
  for (int c = 0; c < 3; ++c) {
    const v1::GridCell& cell = policy.cells(c);
    ASSERT_THAT(cell.run_means(), SizeIs(2));
    seeds_differ |= cell.run_means(0) != cell.run_means(1);
    EXPECT_THAT(cell.returns(), SizeIs(8));
    const double a = cell.run_means(0);
    const double b = cell.run_means(1);
    EXPECT_DOUBLE_EQ(cell.mean(), (a + b) / 2);
    EXPECT_DOUBLE_EQ(cell.std(), std::abs(a - b) / 2);
  }
  EXPECT_TRUE(seeds_differ) << "the two seeds scored alike everywhere: nothing was averaged";
  // Each run's mean is what evaluating that run alone gives.
  const RunResult alone = DcsAt({"eval", policy.runs(1).run(), "--grid", "length=0.3:1.2:3",
                                 "--episodes", "4", "-o", "json"},
                                cluster.coordinator_address());
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  v1::GeneralizationGrid single;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(alone.output, &single).ok());
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(single.policies(0).cells(c).mean(), policy.cells(c).run_means(1)) << "cell " << c;
  }
}

TEST_F(EvalCliTest, OnActorsTheClustersActorsEvaluateTheCellsWithTheSameReturns) {
  ClusterProcesses cluster(absl::Seconds(5));
  StartCoordinatorLearnerAndActors(cluster);
  const std::string run_id = TrainOnCluster(cluster, "actors-run");
  ASSERT_FALSE(run_id.empty());
  const auto jobs_delivered = [&] {
    double jobs = 0;
    for (const std::string actor : {"actor-1", "actor-2"}) {
      const absl::StatusOr<std::string> metrics = testing::HttpGet(cluster.metrics_url(actor));
      EXPECT_TRUE(metrics.ok()) << metrics.status();
      jobs += MetricValue(metrics.value_or(""), "dcs_actor_evaluation_jobs_total");
    }
    return jobs;
  };
  const double jobs_before = jobs_delivered();

  // A 4 x 3 grid, 12 cells, with a seed of its own (not the run's).
  const std::vector<std::string> grid = {"--grid",     "length=0.3:1.2:4", "--grid",
                                         "gravity=5:15:3", "--episodes",    "3",
                                         "--seed",     "5",                "-o",
                                         "json"};
  std::vector<std::string> on_actors = {"eval", run_id, "--on-actors"};
  on_actors.insert(on_actors.end(), grid.begin(), grid.end());
  const RunResult remote = DcsAt(on_actors, cluster.coordinator_address(), absl::Minutes(1));
  ASSERT_EQ(remote.exit_code, 0) << remote.output;
  // The actors ran every cell (and the client none).
  EXPECT_GE(jobs_delivered() - jobs_before, 12) << "logs in " << cluster.dir();

  std::vector<std::string> in_process = {"eval", run_id};
  in_process.insert(in_process.end(), grid.begin(), grid.end());
  const RunResult local = DcsAt(in_process, cluster.coordinator_address());
  ASSERT_EQ(local.exit_code, 0) << local.output;
  v1::GeneralizationGrid remote_grid, local_grid;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(remote.output, &remote_grid).ok())
      << remote.output;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(local.output, &local_grid).ok())
      << local.output;
  ASSERT_THAT(remote_grid.policies(), SizeIs(1));
  ASSERT_THAT(remote_grid.policies(0).cells(), SizeIs(12));
  // Bit for bit: every cell's context, returns, mean and std, as serialised doubles.
  EXPECT_EQ(remote_grid.SerializeAsString(), local_grid.SerializeAsString());
  EXPECT_EQ(remote.output, local.output);
}

TEST_F(EvalCliTest, OnActorsARunDirectoryIsRefused) {
  ExpectRefused({Run(), "--grid", "length=0.1:1:3", "--on-actors"},
                "INVALID_ARGUMENT: --on-actors evaluates runs of the cluster; " + Run() +
                    " is a directory here",
                services::kExitDataError);
}

}  // namespace
}  // namespace dcs::integration
