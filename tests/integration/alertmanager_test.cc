// Copyright 2026 The DCS Authors.
//
// deploy/alertmanager/alertmanager.yml against a real Alertmanager (Debian's package): the
// project's config, with its receiver's URL pointed at a webhook this test serves, is sent
// alerts as Prometheus sends them (Alertmanager's v2 API; labels and annotations from
// deploy/prometheus/rules.yml). Firing alerts reach the receiver; those that a firing alert
// inhibits (a coordinator down: workers cut off, workers lost; actors down: actors lost) do
// not, and Alertmanager says which alert inhibits them.
//
// Alerts are posted rather than raised by a real Prometheus: promtool's tests
// (deploy/prometheus/rules_test.yml) show when each rule fires, `for:` included; what they
// cannot show is the path from a firing alert to the receiver (route, receiver, inhibitions),
// and posting reaches it without waiting out a `for:` on processes made to fail.

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <httplib.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "common/atomic_file.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "tests/integration/test_util.h"
#include "tests/testing/eventually.h"
#include "tests/testing/net.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

namespace fs = std::filesystem;
using google::protobuf::Struct;
using google::protobuf::Value;

const fs::path kDeploy = fs::path(DCS_SOURCE_DIR) / "deploy";
// Alertmanager's route waits group_wait (30 s) before a group's first notification.
constexpr absl::Duration kDelivery = absl::Minutes(2);

// An alert by its name, and its role if it has one: "DcsWorkerLost role=learner".
std::string Describe(const Value& alert) {
  const Value& labels = JsonField(alert, "labels");
  const std::string role = JsonField(labels, "role").string_value();
  return absl::StrCat(JsonField(labels, "alertname").string_value(),
                      role.empty() ? "" : absl::StrCat(" role=", role));
}

// Receives Alertmanager's webhook notifications on a free loopback port. Thread-safe.
class Webhook {
 public:
  Webhook() {
    server_.Post("/alerts", [this](const httplib::Request& request, httplib::Response&) {
      absl::MutexLock lock(&mu_);
      bodies_.push_back(request.body);
    });
    port_ = server_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
  }
  ~Webhook() {
    server_.stop();
    thread_.join();
  }

  std::string url() const { return absl::StrCat("http://127.0.0.1:", port_, "/alerts"); }

  // Every alert of every notification received so far: its name, and its role if it has one
  // ("DcsWorkerLost role=learner").
  std::multiset<std::string> Received() const {
    std::multiset<std::string> received;
    absl::MutexLock lock(&mu_);
    for (const std::string& body : bodies_) {
      absl::StatusOr<Value> notification = ParseJsonValue(body);
      EXPECT_TRUE(notification.ok()) << body;
      if (!notification.ok()) continue;
      for (const Value& alert : JsonField(*notification, "alerts").list_value().values()) {
        received.insert(Describe(alert));
      }
    }
    return received;
  }

 private:
  httplib::Server server_;
  int port_ = 0;
  std::thread thread_;
  mutable absl::Mutex mu_;
  std::vector<std::string> bodies_ ABSL_GUARDED_BY(mu_);
};

// deploy/alertmanager/alertmanager.yml with its one webhook receiver's URL replaced by `url`.
// Returns the written config's path.
std::string WriteConfig(const std::string& dir, const std::string& url) {
  YAML::Node config = YAML::LoadFile(kDeploy / "alertmanager/alertmanager.yml");
  EXPECT_EQ(config["receivers"].size(), 1u);
  YAML::Node webhooks = config["receivers"][0]["webhook_configs"];
  EXPECT_EQ(webhooks.size(), 1u);
  webhooks[0]["url"] = url;
  const std::string path = absl::StrCat(dir, "/alertmanager.yml");
  YAML::Emitter out;
  out << config;
  EXPECT_TRUE(WriteFileAtomically(path, out.c_str()).ok());
  return path;
}

// Alertmanager on a free loopback port, alone (no cluster gossip), logging at debug level.
class Alertmanager {
 public:
  Alertmanager(const std::string& dir, const std::string& config)
      : web_(absl::StrCat("127.0.0.1:", testing::PickFreePort())),
        log_(absl::StrCat(dir, "/alertmanager.log")) {
    absl::StatusOr<services::cli::ChildProcess> process = services::cli::ChildProcess::Start(
        {.path = "/usr/bin/prometheus-alertmanager",
         .args = {absl::StrCat("--config.file=", config),
                  absl::StrCat("--storage.path=", dir, "/data"),
                  absl::StrCat("--web.listen-address=", web_), "--cluster.listen-address=",
                  "--log.level=debug"},
         .output_path = log_});
    EXPECT_TRUE(process.ok()) << process.status();
    if (process.ok()) process_ = std::make_unique<services::cli::ChildProcess>(*std::move(process));
  }
  ~Alertmanager() {
    if (process_ != nullptr) process_->Stop(absl::Seconds(5));
  }

  bool WaitReady() const {
    return testing::Eventually(
        [&] { return testing::HttpGet(absl::StrCat("http://", web_, "/-/ready")).ok(); },
        absl::Seconds(30), absl::Milliseconds(100));
  }

  // Posts `alerts` (a JSON array) as Prometheus does.
  bool Post(const std::string& alerts) const {
    httplib::Client client(absl::StrCat("http://", web_));
    const httplib::Result result = client.Post("/api/v2/alerts", alerts, "application/json");
    EXPECT_TRUE(result && result->status == 200)
        << (result ? result->body : httplib::to_string(result.error()));
    return result && result->status == 200;
  }

  // Every alert Alertmanager holds (labels, fingerprint, status: state and inhibitedBy).
  std::vector<Value> Alerts() const {
    absl::StatusOr<std::string> body = testing::HttpGet(absl::StrCat("http://", web_,
                                                                     "/api/v2/alerts"));
    EXPECT_TRUE(body.ok()) << body.status();
    absl::StatusOr<Value> list = ParseJsonValue(body.value_or("[]"));
    EXPECT_TRUE(list.ok()) << list.status();
    if (!list.ok()) return {};
    return {list->list_value().values().begin(), list->list_value().values().end()};
  }

  // Whether Alertmanager has flushed `alert`'s group: the moment it sends the group's
  // notification, or, with every alert of the group inhibited, sends none (it logs the flush).
  bool LoggedFlush(const std::string& alert) const {
    absl::StatusOr<std::string> log = ReadFile(log_);
    if (!log.ok()) return false;
    for (absl::string_view line : absl::StrSplit(*log, '\n')) {
      if (absl::StrContains(line, "msg=flushing") &&
          absl::StrContains(line, absl::StrCat("alerts=[", alert, "["))) {
        return true;
      }
    }
    return false;
  }

  const std::string& log() const { return log_; }

 private:
  std::string web_;
  std::string log_;
  std::unique_ptr<services::cli::ChildProcess> process_;
};

// An alert of deploy/prometheus/rules.yml as Prometheus posts it while it fires: its name, its
// rule's labels and annotations (their templates as written) and `labels`, for 10 minutes.
Value FiringAlert(const std::string& name, const std::map<std::string, std::string>& labels) {
  Value alert;
  Struct& fields = *alert.mutable_struct_value();
  Struct& alert_labels = *(*fields.mutable_fields())["labels"].mutable_struct_value();
  (*alert_labels.mutable_fields())["alertname"].set_string_value(name);
  for (const auto& [key, value] : labels) {
    (*alert_labels.mutable_fields())[key].set_string_value(value);
  }
  const YAML::Node rules = YAML::LoadFile(kDeploy / "prometheus/rules.yml");
  bool found = false;
  for (const YAML::Node& group : rules["groups"]) {
    for (const YAML::Node& rule : group["rules"]) {
      if (!rule["alert"] || rule["alert"].as<std::string>() != name) continue;
      found = true;
      for (const auto& label : rule["labels"]) {
        (*alert_labels.mutable_fields())[label.first.as<std::string>()].set_string_value(
            label.second.as<std::string>());
      }
      Struct& annotations = *(*fields.mutable_fields())["annotations"].mutable_struct_value();
      for (const auto& annotation : rule["annotations"]) {
        (*annotations.mutable_fields())[annotation.first.as<std::string>()].set_string_value(
            annotation.second.as<std::string>());
      }
    }
  }
  EXPECT_TRUE(found) << name << " is not an alert of rules.yml";
  const absl::Time now = absl::Now();
  (*fields.mutable_fields())["startsAt"].set_string_value(absl::FormatTime(now));
  (*fields.mutable_fields())["endsAt"].set_string_value(
      absl::FormatTime(now + absl::Minutes(10)));
  return alert;
}

std::string ToJson(const std::vector<Value>& alerts) {
  Value list;
  for (const Value& alert : alerts) *list.mutable_list_value()->add_values() = alert;
  std::string json;
  EXPECT_TRUE(google::protobuf::util::MessageToJsonString(list, &json).ok());
  return json;
}

// The project's Alertmanager, delivering to a webhook of the test's.
class AlertmanagerTest : public ::testing::Test {
 protected:
  AlertmanagerTest()
      : dir_(testing::MakeTempDir()), alertmanager_(dir_, WriteConfig(dir_, webhook_.url())) {}

  // Waits until the receiver has `delivered` (each alert as Describe names it) and
  // Alertmanager has flushed the groups of `held_back` too; then the receiver must have
  // received `delivered` alone.
  void ExpectDeliveredAndHeldBack(const std::multiset<std::string>& delivered,
                                  const std::vector<std::string>& held_back) {
    EXPECT_TRUE(testing::Eventually(
        [&] {
          const std::multiset<std::string> received = webhook_.Received();
          return std::includes(received.begin(), received.end(), delivered.begin(),
                               delivered.end());
        },
        kDelivery, absl::Milliseconds(250)))
        << "see " << alertmanager_.log();
    for (const std::string& alert : held_back) {
      EXPECT_TRUE(testing::Eventually([&] { return alertmanager_.LoggedFlush(alert); },
                                      kDelivery, absl::Milliseconds(250)))
          << alert << "'s group was never flushed; see " << alertmanager_.log();
    }
    EXPECT_EQ(webhook_.Received(), delivered);
  }

  // The fingerprints of the alerts that inhibit `alert` (Describe's name), as Alertmanager
  // reports them; "" for an alert it does not hold.
  std::string InhibitedBy(const std::string& alert) const {
    for (const Value& held : alertmanager_.Alerts()) {
      if (Describe(held) != alert) continue;
      std::vector<std::string> by;
      for (const Value& fingerprint :
           JsonField(JsonField(held, "status"), "inhibitedBy").list_value().values()) {
        by.push_back(fingerprint.string_value());
      }
      return absl::StrJoin(by, ",");
    }
    return "";
  }

  std::string Fingerprint(const std::string& alert) const {
    for (const Value& held : alertmanager_.Alerts()) {
      if (Describe(held) == alert) return JsonField(held, "fingerprint").string_value();
    }
    return "";
  }

  const std::string dir_;
  Webhook webhook_;
  Alertmanager alertmanager_;
};

TEST_F(AlertmanagerTest, ACoordinatorDownHoldsBackWorkersCutOffAndLostButNotAFailedRun) {
  ASSERT_TRUE(alertmanager_.WaitReady()) << "see " << alertmanager_.log();
  ASSERT_TRUE(alertmanager_.Post(ToJson({
      FiringAlert("DcsCoordinatorDown", {{"job", "coordinator"}, {"instance", "c:9464"}}),
      FiringAlert("DcsWorkersCutOff", {{"job", "actor"}}),
      FiringAlert("DcsWorkerLost",
                  {{"job", "coordinator"}, {"instance", "c:9464"}, {"role", "actor"}}),
      FiringAlert("DcsRunsFailed", {{"job", "coordinator"}, {"instance", "c:9464"}}),
  })));

  ExpectDeliveredAndHeldBack({"DcsCoordinatorDown", "DcsRunsFailed"},
                             {"DcsWorkersCutOff", "DcsWorkerLost"});
  const std::string coordinator_down = Fingerprint("DcsCoordinatorDown");
  ASSERT_FALSE(coordinator_down.empty());
  EXPECT_EQ(InhibitedBy("DcsWorkersCutOff"), coordinator_down);
  EXPECT_EQ(InhibitedBy("DcsWorkerLost role=actor"), coordinator_down);
  EXPECT_EQ(InhibitedBy("DcsRunsFailed"), "");
  EXPECT_EQ(InhibitedBy("DcsCoordinatorDown"), "");
}

// Within one notification: of two workers lost, the actor is explained by the actors down and
// left out, the learner is not.
TEST_F(AlertmanagerTest, ActorsDownHoldBackAnActorLostButNotALearnerLost) {
  ASSERT_TRUE(alertmanager_.WaitReady()) << "see " << alertmanager_.log();
  ASSERT_TRUE(alertmanager_.Post(ToJson({
      FiringAlert("DcsActorsDown", {{"job", "actor"}}),
      FiringAlert("DcsWorkerLost",
                  {{"job", "coordinator"}, {"instance", "c:9464"}, {"role", "actor"}}),
      FiringAlert("DcsWorkerLost",
                  {{"job", "coordinator"}, {"instance", "c:9464"}, {"role", "learner"}}),
  })));

  ExpectDeliveredAndHeldBack({"DcsActorsDown", "DcsWorkerLost role=learner"}, {});
  EXPECT_EQ(InhibitedBy("DcsWorkerLost role=actor"), Fingerprint("DcsActorsDown"));
  EXPECT_EQ(InhibitedBy("DcsWorkerLost role=learner"), "");
}

}  // namespace
}  // namespace dcs::integration
