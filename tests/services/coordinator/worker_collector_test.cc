// Copyright 2026 The DCS Authors.
#include "services/coordinator/worker_collector.h"

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "coordinator/worker_registry.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

// {role, state} -> value of the single dcs_workers family.
std::map<std::pair<std::string, std::string>, double> Counts(const WorkerCollector& collector) {
  std::map<std::pair<std::string, std::string>, double> counts;
  const std::vector<prometheus::MetricFamily> families = collector.Collect();
  EXPECT_EQ(families.size(), 1u);
  for (const prometheus::MetricFamily& family : families) {
    EXPECT_EQ(family.name, "dcs_workers");
    EXPECT_EQ(family.type, prometheus::MetricType::Gauge);
    for (const prometheus::ClientMetric& metric : family.metric) {
      std::string role;
      std::string state;
      for (const prometheus::ClientMetric::Label& label : metric.label) {
        if (label.name == "role") role = label.value;
        if (label.name == "state") state = label.value;
      }
      counts[{role, state}] = metric.gauge.value;
    }
  }
  return counts;
}

std::unique_ptr<coordinator::WorkerRegistry> NewRegistry() {
  // Wide margins around the real clock, which WorkerCollector reads.
  auto registry = coordinator::WorkerRegistry::Create({.heartbeat_interval = absl::Seconds(1),
                                                       .lost_after = absl::Minutes(1),
                                                       .forget_after = absl::Hours(1)});
  EXPECT_TRUE(registry.ok()) << registry.status();
  return registry.ok() ? *std::move(registry) : nullptr;
}

TEST(WorkerCollectorTest, ReportsEveryRoleAndStateAtZero) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::map<std::pair<std::string, std::string>, double> expected = {{{"learner", "alive"}, 0},
                                                                          {{"learner", "lost"}, 0},
                                                                          {{"actor", "alive"}, 0},
                                                                          {{"actor", "lost"}, 0}};
  EXPECT_EQ(Counts(WorkerCollector(*registry)), expected);
}

TEST(WorkerCollectorTest, CountsByRoleAndStateAtScrapeTime) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const absl::Time now = absl::Now();
  const WorkerInfo actor{.role = WorkerRole::kActor, .address = "h:1"};
  const WorkerInfo learner{.role = WorkerRole::kLearner, .address = "h:2"};
  ASSERT_TRUE(registry->Register(actor, now).ok());
  ASSERT_TRUE(registry->Register(actor, now).ok());
  // Silent for 10 minutes: LOST (but not forgotten) by the time of the scrape.
  ASSERT_TRUE(registry->Register(actor, now - absl::Minutes(10)).ok());
  ASSERT_TRUE(registry->Register(learner, now - absl::Minutes(10)).ok());

  const std::map<std::pair<std::string, std::string>, double> expected = {{{"learner", "alive"}, 0},
                                                                          {{"learner", "lost"}, 1},
                                                                          {{"actor", "alive"}, 2},
                                                                          {{"actor", "lost"}, 1}};
  EXPECT_EQ(Counts(WorkerCollector(*registry)), expected);
}

}  // namespace
}  // namespace dcs::services
