// Copyright 2026 The DCS Authors.
//
// deploy/ against a real Prometheus (Debian's package): a local
// cluster (`dcs up`'s LocalCluster) runs a small sweep while Prometheus, configured by
// deploy/prometheus/local.yml and its rules, scrapes every process through the targets file the
// cluster writes. Then every query of every Grafana dashboard panel and variable, and every
// recording rule, must return data over the sweep's time through Prometheus's HTTP API; every
// alert's expression must be valid PromQL. The dashboards' JSON is checked as Grafana's file
// provisioning reads it: unique uids, and every datasource the provisioned uid. The sweep's
// final tally and best condition must be readable after it ended, as `dcs watch` named it.
//
// Apart, on a cluster whose learner is killed mid-run: the run's step as Prometheus scraped it
// from the coordinator never goes down, although another learner resumes the run from an older
// checkpoint.

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_replace.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "services/cli/local_cluster.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/net.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {
namespace {

namespace fs = std::filesystem;
using google::protobuf::Struct;
using google::protobuf::Value;

const fs::path kDeploy = fs::path(DCS_SOURCE_DIR) / "deploy";
constexpr char kDatasourceUid[] = "prometheus";  // deploy/grafana/provisioning/datasources

// A CartPole sweep of `conditions` (the YAML list's items), one seed, each run of `total` steps
// evaluated every `evaluation_freq` (and checkpointed after each evaluation).
std::string CartPoleSpec(const std::string& name, int64_t total, int64_t evaluation_freq,
                         const std::string& conditions) {
  return absl::StrCat("name: ", name, "\nseeds: 1\nenv: cartpole\ntotal_timesteps: ", total,
                      R"(
feature: length
training_range: [0.35, 0.75]
evaluation: {freq: )",
                      evaluation_freq, R"(, episodes: 2,
             contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0]}}
ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}
conditions:
)",
                      conditions);
}

absl::StatusOr<Struct> ParseJson(const std::string& text) {
  Struct parsed;
  const auto status = google::protobuf::util::JsonStringToMessage(text, &parsed);
  if (!status.ok()) return absl::InvalidArgumentError(status.ToString());
  return parsed;
}

const Value& Field(const Struct& object, const std::string& name) {
  static const Value kNull;
  const auto found = object.fields().find(name);
  return found == object.fields().end() ? kNull : found->second;
}

// Prometheus on a free loopback port, with a private data directory.
class Prometheus {
 public:
  Prometheus(const std::string& dir, const std::string& config)
      : web_(absl::StrCat("127.0.0.1:", testing::PickFreePort())) {
    absl::StatusOr<services::cli::ChildProcess> process = services::cli::ChildProcess::Start(
        {.path = "/usr/bin/prometheus",
         .args = {absl::StrCat("--config.file=", config),
                  absl::StrCat("--storage.tsdb.path=", dir, "/tsdb"),
                  absl::StrCat("--web.listen-address=", web_)},
         .output_path = absl::StrCat(dir, "/prometheus.log")});
    EXPECT_TRUE(process.ok()) << process.status();
    if (process.ok()) process_ = std::make_unique<services::cli::ChildProcess>(*std::move(process));
  }
  ~Prometheus() {
    if (process_ != nullptr) process_->Stop(absl::Seconds(5));
  }

  // The `data` of an API call's answer; an error if the call fails or is not "success".
  absl::StatusOr<Struct> Api(const std::string& path_and_query) const {
    absl::StatusOr<std::string> body =
        testing::HttpGet(absl::StrCat("http://", web_, path_and_query));
    if (!body.ok()) return body.status();
    absl::StatusOr<Struct> answer = ParseJson(*body);
    if (!answer.ok()) return answer.status();
    if (Field(*answer, "status").string_value() != "success") {
      return absl::InvalidArgumentError(*body);
    }
    return Field(*answer, "data").struct_value();
  }

  // The series `expr` gives over [start, end] at 1-second steps: each with its "metric" (the
  // labels) and "values" ([time, "value"] pairs).
  absl::StatusOr<std::vector<Struct>> Range(const std::string& expr, absl::Time start,
                                            absl::Time end) const {
    return Series(Api(absl::StrCat("/api/v1/query_range?query=", testing::UrlEncode(expr),
                                   "&start=", absl::ToUnixSeconds(start),
                                   "&end=", absl::ToUnixSeconds(end), "&step=1")));
  }
  absl::StatusOr<int> SeriesOver(const std::string& expr, absl::Time start, absl::Time end) const {
    absl::StatusOr<std::vector<Struct>> series = Range(expr, start, end);
    if (!series.ok()) return series.status();
    return static_cast<int>(series->size());
  }

  // The series `expr` gives at `time`: each with its "metric" and "value" ([time, "value"]).
  absl::StatusOr<std::vector<Struct>> At(const std::string& expr, absl::Time time) const {
    return Series(Api(absl::StrCat("/api/v1/query?query=", testing::UrlEncode(expr),
                                   "&time=", absl::ToUnixSeconds(time))));
  }

  // The `result` list of an API call's `data`.
  static absl::StatusOr<std::vector<Struct>> Series(const absl::StatusOr<Struct>& data) {
    if (!data.ok()) return data.status();
    std::vector<Struct> series;
    for (const Value& one : Field(*data, "result").list_value().values()) {
      series.push_back(one.struct_value());
    }
    return series;
  }

  // Waits until Prometheus scrapes `targets` targets, every one up.
  bool WaitForTargetsUp(int targets) const {
    const absl::Time deadline = absl::Now() + testing::Patient(absl::Seconds(60));
    while (absl::Now() < deadline) {
      absl::StatusOr<Struct> data = Api("/api/v1/targets?state=active");
      if (data.ok()) {
        const auto& active = Field(*data, "activeTargets").list_value().values();
        int up = 0;
        for (const Value& target : active) {
          up += Field(target.struct_value(), "health").string_value() == "up";
        }
        if (active.size() == targets && up == targets) return true;
      }
      absl::SleepFor(absl::Milliseconds(250));
    }
    return false;
  }

 private:
  std::string web_;
  std::unique_ptr<services::cli::ChildProcess> process_;
};

// deploy/prometheus/local.yml as the test runs it: scraping and evaluating every second, its
// targets file and rules by absolute path. Returns the written config's path.
std::string WriteLocalConfig(const std::string& dir, const std::string& targets_file) {
  YAML::Node config = YAML::LoadFile(kDeploy / "prometheus/local.yml");
  config["global"]["scrape_interval"] = "1s";
  config["global"]["evaluation_interval"] = "1s";
  EXPECT_EQ(config["rule_files"].size(), 1u);
  config["rule_files"][0] =
      (kDeploy / "prometheus" / config["rule_files"][0].as<std::string>()).string();
  YAML::Node files = config["scrape_configs"][0]["file_sd_configs"][0]["files"];
  EXPECT_EQ(files.size(), 1u);
  files[0] = targets_file;
  const std::string path = absl::StrCat(dir, "/prometheus.yml");
  YAML::Emitter out;
  out << config;
  EXPECT_TRUE(WriteFileAtomically(path, out.c_str()).ok());
  return path;
}

// A panel's or variable's PromQL with Grafana's variables replaced: the sweep under test, every
// condition, run and instance, and a rate window of several scrapes.
std::string Substitute(const std::string& expr, const std::string& sweep_id) {
  return absl::StrReplaceAll(expr, {{"$__rate_interval", "10s"},
                                    {"$sweep", sweep_id},
                                    {"$condition", ".*"},
                                    {"$run", ".*"},
                                    {"$instance", ".*"}});
}

// Series the test's sweep cannot have, so their queries need only run: CartPole's policy is
// categorical, and only a Gaussian policy has a std.
bool NoSeriesForTheTestSweep(const std::string& expr) {
  return absl::StrContains(expr, "dcs_policy_std");
}

// A sample's value ("value": [time, "number"]).
double SampleValue(const Struct& sample) {
  double value = 0;
  EXPECT_TRUE(absl::SimpleAtod(Field(sample, "value").list_value().values(1).string_value(),
                               &value));
  return value;
}

// A series' label `name`.
std::string Label(const Struct& series, const std::string& name) {
  return Field(Field(series, "metric").struct_value(), name).string_value();
}

// Where a query comes from, for failure messages.
struct Query {
  std::string where;
  std::string expr;
};

// Every panel's and variable's query in dashboard `file`; checks its uids on the way.
std::vector<Query> DashboardQueries(const fs::path& file, std::set<std::string>& uids) {
  std::vector<Query> queries;
  absl::StatusOr<std::string> text = ReadFile(file);
  EXPECT_TRUE(text.ok()) << text.status();
  absl::StatusOr<Struct> dashboard = ParseJson(text.value_or(""));
  EXPECT_TRUE(dashboard.ok()) << file << ": " << dashboard.status();
  if (!dashboard.ok()) return queries;
  const std::string uid = Field(*dashboard, "uid").string_value();
  EXPECT_FALSE(uid.empty()) << file;
  EXPECT_TRUE(uids.insert(uid).second) << file << " repeats dashboard uid " << uid;
  EXPECT_TRUE(Field(*dashboard, "id").has_null_value()) << file << ": provisioned with an id";
  auto expect_datasource = [&](const Struct& owner, const std::string& where) {
    EXPECT_EQ(Field(Field(owner, "datasource").struct_value(), "uid").string_value(),
              kDatasourceUid)
        << where;
  };
  for (const Value& variable :
       Field(Field(*dashboard, "templating").struct_value(), "list").list_value().values()) {
    const Struct& v = variable.struct_value();
    const std::string where =
        absl::StrCat(file.filename().string(), " variable ", Field(v, "name").string_value());
    expect_datasource(v, where);
    queries.push_back({where, Field(Field(v, "query").struct_value(), "query").string_value()});
  }
  for (const Value& panel : Field(*dashboard, "panels").list_value().values()) {
    const Struct& p = panel.struct_value();
    if (Field(p, "type").string_value() == "row") continue;
    const std::string where =
        absl::StrCat(file.filename().string(), " panel \"", Field(p, "title").string_value(), "\"");
    expect_datasource(p, where);
    const auto& targets = Field(p, "targets").list_value().values();
    EXPECT_FALSE(targets.empty()) << where << " has no query";
    for (const Value& target : targets) {
      expect_datasource(target.struct_value(), where);
      queries.push_back({where, Field(target.struct_value(), "expr").string_value()});
    }
  }
  return queries;
}

TEST(PrometheusTest, EveryDashboardQueryAndRecordingRuleReturnsDataFromARealPrometheus) {
  const std::string dir = testing::MakeTempDir();
  const std::string data_dir = absl::StrCat(dir, "/dcs-data");
  absl::StatusOr<std::unique_ptr<services::cli::LocalCluster>> cluster =
      services::cli::LocalCluster::Start({.data_dir = data_dir, .bin_dir = BinDir(), .actors = 2});
  ASSERT_TRUE(cluster.ok()) << cluster.status();
  const std::string config =
      WriteLocalConfig(dir, absl::StrCat(data_dir, "/prometheus-targets.yml"));
  const RunResult checked = RunProgram("/usr/bin/promtool", {"check", "config", config});
  ASSERT_EQ(checked.exit_code, 0) << checked.output;

  Prometheus prometheus(dir, config);
  ASSERT_TRUE(prometheus.WaitForTargetsUp(4))  // coordinator, learner, two actors
      << "see " << dir << "/prometheus.log";

  // The sweep, watched to its end; then two more scrapes and rule evaluations.
  const std::string spec = absl::StrCat(dir, "/watched.yaml");
  // Two conditions: CartPole learns at tens of thousands of steps per second here, so each
  // run takes some 15 s, for several scrapes and evaluations of each.
  ASSERT_TRUE(WriteFileAtomically(
                  spec, CartPoleSpec("watched", 655360, 131072,
                                     "  - name: static\n"
                                     "  - schedule: {family: sinusoidal, amplitude_frac: 0.5, "
                                     "period: 40}\n"))
                  .ok());
  const absl::Time start = absl::Now();
  const RunResult submitted =
      DcsAt({"submit", spec, "--watch"}, (*cluster)->state().coordinator_address, absl::Minutes(5));
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  ASSERT_THAT(submitted.output, ::testing::HasSubstr("sweep-1 watched: completed"));
  absl::SleepFor(absl::Seconds(3));
  const absl::Time end = absl::Now();

  std::vector<Query> queries;
  std::set<std::string> uids;
  for (const fs::directory_entry& file : fs::directory_iterator(kDeploy / "grafana/dashboards")) {
    std::vector<Query> more = DashboardQueries(file.path(), uids);
    queries.insert(queries.end(), more.begin(), more.end());
  }
  EXPECT_EQ(uids, (std::set<std::string>{"dcs-cluster", "dcs-sweeps", "dcs-training"}));
  for (const Query& query : queries) {
    // A variable's label_values(SELECTOR, LABEL) asks for SELECTOR's series.
    std::string expr = Substitute(query.expr, "sweep-1");
    constexpr absl::string_view kLabelValues = "label_values(";
    if (absl::StartsWith(expr, kLabelValues)) {
      expr = expr.substr(kLabelValues.size(), expr.rfind(',') - kLabelValues.size());
    }
    absl::StatusOr<int> series = prometheus.SeriesOver(expr, start, end);
    ASSERT_TRUE(series.ok()) << query.where << ": " << expr << ": " << series.status();
    if (NoSeriesForTheTestSweep(expr)) continue;
    EXPECT_GT(*series, 0) << query.where << " has no data: " << expr;
  }

  // After the sweep ended: its final tally, and its best condition as `dcs watch` named it.
  std::smatch best;
  ASSERT_TRUE(std::regex_search(submitted.output, best,
                                std::regex(R"(best: (\S+) \((\S+)\) (-?[0-9.]+))")))
      << submitted.output;
  absl::StatusOr<std::vector<Struct>> best_series =
      prometheus.At(R"(dcs_sweep_best_avg_combined{sweep_id="sweep-1"})", end);
  ASSERT_TRUE(best_series.ok()) << best_series.status();
  ASSERT_EQ(best_series->size(), 1u);
  EXPECT_EQ(Label(best_series->front(), "condition"), best[1].str());
  EXPECT_EQ(Label(best_series->front(), "observe"), best[2].str());
  EXPECT_EQ(absl::StrFormat("%.1f", SampleValue(best_series->front())), best[3].str());
  absl::StatusOr<std::vector<Struct>> tally =
      prometheus.At(R"(dcs_sweep_runs{sweep_id="sweep-1"})", end);
  ASSERT_TRUE(tally.ok()) << tally.status();
  std::map<std::string, double> runs_by_state;
  for (const Struct& series : *tally) runs_by_state[Label(series, "state")] = SampleValue(series);
  EXPECT_EQ(runs_by_state, (std::map<std::string, double>{{"queued", 0},
                                                          {"running", 0},
                                                          {"completed", 2},
                                                          {"failed", 0},
                                                          {"cancelled", 0}}));

  const YAML::Node rules = YAML::LoadFile(kDeploy / "prometheus/rules.yml");
  int recorded = 0;
  for (const YAML::Node& group : rules["groups"]) {
    for (const YAML::Node& rule : group["rules"]) {
      if (rule["record"]) {
        const std::string name = rule["record"].as<std::string>();
        absl::StatusOr<int> series = prometheus.SeriesOver(name, start, end);
        ASSERT_TRUE(series.ok()) << name << ": " << series.status();
        EXPECT_GT(*series, 0) << "recording rule " << name << " has no data";
        ++recorded;
      } else {
        // An alert need not fire here, but its expression must be one Prometheus runs.
        const std::string expr = rule["expr"].as<std::string>();
        EXPECT_TRUE(prometheus.SeriesOver(expr, start, end).ok())
            << "alert " << rule["alert"].as<std::string>() << ": " << expr;
      }
    }
  }
  EXPECT_GT(recorded, 0);
}

TEST(PrometheusTest, ARunsStepNeverGoesDownAcrossALearnerHandover) {
  ClusterProcesses cluster(absl::Seconds(2));  // short leases: the handover is quick
  StartCoordinatorLearnerAndActors(cluster);
  // Prometheus scrapes the coordinator as `dcs up`'s targets file labels it.
  const std::string metrics_url = cluster.metrics_url("coordinator");  // http://H:P/metrics
  const std::string host_port =
      metrics_url.substr(std::string("http://").size(),
                         metrics_url.size() - std::string("http://").size() -
                             std::string("/metrics").size());
  const std::string targets = absl::StrCat(cluster.dir(), "/targets.yml");
  ASSERT_TRUE(WriteFileAtomically(targets, absl::StrCat("- targets: [\"", host_port,
                                                        "\"]\n  labels: {job: coordinator}\n"))
                  .ok());
  Prometheus prometheus(cluster.dir(), WriteLocalConfig(cluster.dir(), targets));
  ASSERT_TRUE(prometheus.WaitForTargetsUp(1)) << "see " << cluster.dir() << "/prometheus.log";

  // One run, checkpointed after its evaluations half way and at the end.
  constexpr int64_t kTotal = 4194304;
  const std::string spec = absl::StrCat(cluster.dir(), "/one.yaml");
  ASSERT_TRUE(
      WriteFileAtomically(spec, CartPoleSpec("one", kTotal, kTotal / 2, "  - name: static\n"))
          .ok());
  const absl::Time start = absl::Now();
  const RunResult submitted = DcsAt({"submit", spec}, cluster.coordinator_address());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;

  // Once Prometheus has scraped a step well past the first checkpoint, the learner dies, and
  // another takes the run over.
  double before_kill = -1;
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(3));
  while (before_kill < kTotal * 5 / 8 && absl::Now() < deadline) {
    absl::SleepFor(absl::Milliseconds(100));
    absl::StatusOr<std::vector<Struct>> now =
        prometheus.At(R"(dcs_run_step{run_id="run-1"})", absl::Now());
    if (now.ok() && now->size() == 1) before_kill = SampleValue(now->front());
  }
  ASSERT_GE(before_kill, kTotal * 5 / 8) << "the run did not get there in time";
  cluster.Kill("learner");
  cluster.StartLearner("learner-2");
  const RunResult watched =
      DcsAt({"watch", "sweep-1"}, cluster.coordinator_address(), absl::Minutes(5));
  ASSERT_THAT(watched.output, ::testing::HasSubstr("sweep-1 one: completed"));
  absl::SleepFor(absl::Seconds(2));
  const absl::Time end = absl::Now();

  // The new learner resumed from an older checkpoint (or none), below the step reached: its
  // reports went back, and a step series that followed them would have fallen.
  std::smatch resumed;
  const std::string log = cluster.Log("learner-2");
  const std::regex hosting("hosting a run run_id=run-1 .*checkpoint=([0-9]+|none)");
  ASSERT_TRUE(std::regex_search(log, resumed, hosting)) << log;
  int64_t resumed_at = 0;
  ASSERT_TRUE(resumed[1] == "none" || absl::SimpleAtoi(resumed[1].str(), &resumed_at));
  ASSERT_LT(static_cast<double>(resumed_at + 256), before_kill);

  absl::StatusOr<std::vector<Struct>> step =
      prometheus.Range(R"(dcs_run_step{run_id="run-1"})", start, end);
  ASSERT_TRUE(step.ok()) << step.status();
  ASSERT_EQ(step->size(), 1u);
  double previous = 0;
  double highest = 0;
  for (const Value& sample : Field(step->front(), "values").list_value().values()) {
    double value = 0;
    ASSERT_TRUE(absl::SimpleAtod(sample.list_value().values(1).string_value(), &value));
    EXPECT_GE(value, previous) << "dcs_run_step went down at "
                               << sample.list_value().values(0).number_value();
    previous = value;
    highest = std::max(highest, value);
  }
  EXPECT_GE(highest, before_kill);
}

}  // namespace
}  // namespace dcs::integration
