// Copyright 2026 The DCS Authors.
//
// deploy/ against a real Prometheus (Debian's package): a local
// cluster (`dcs up`'s LocalCluster) runs a small sweep while Prometheus, configured by
// deploy/prometheus/local.yml and its rules, scrapes every process through the targets file the
// cluster writes. Then every query of every Grafana dashboard panel and variable, and every
// recording rule, must return data over the sweep's time through Prometheus's HTTP API; every
// alert's expression must be valid PromQL. The dashboards' JSON is checked as Grafana's file
// provisioning reads it: unique uids, and every datasource the provisioned uid.

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "services/cli/local_cluster.h"
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

// Two conditions, one seed: CartPole learns at tens of thousands of steps per second here, so
// each run takes some 15 s, for several scrapes and evaluations of each.
constexpr char kSpec[] = R"(name: watched
seeds: 1
env: cartpole
total_timesteps: 655360
feature: length
training_range: [0.35, 0.75]
evaluation: {freq: 131072, episodes: 2, contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0]}}
ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}
conditions:
  - name: static
  - schedule: {family: sinusoidal, amplitude_frac: 0.5, period: 40}
)";

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

  // The series `expr` gives over [start, end] at 1-second steps.
  absl::StatusOr<int> SeriesOver(const std::string& expr, absl::Time start, absl::Time end) const {
    absl::StatusOr<Struct> data = Api(absl::StrCat(
        "/api/v1/query_range?query=", testing::UrlEncode(expr),
        "&start=", absl::ToUnixSeconds(start), "&end=", absl::ToUnixSeconds(end), "&step=1"));
    if (!data.ok()) return data.status();
    return Field(*data, "result").list_value().values_size();
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
// condition and run, and a rate window of several scrapes.
std::string Substitute(const std::string& expr, const std::string& sweep_id) {
  return absl::StrReplaceAll(
      expr,
      {{"$__rate_interval", "10s"}, {"$sweep", sweep_id}, {"$condition", ".*"}, {"$run", ".*"}});
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
  ASSERT_TRUE(WriteFileAtomically(spec, kSpec).ok());
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
    EXPECT_GT(*series, 0) << query.where << " has no data: " << expr;
  }

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

}  // namespace
}  // namespace dcs::integration
