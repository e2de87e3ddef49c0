// Copyright 2026 The DCS Authors.
#include "services/refusal_counter.h"

#include <prometheus/registry.h>

#include <map>
#include <string>

#include "absl/status/status.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

std::map<std::string, double> ByReason(prometheus::Registry& registry) {
  std::map<std::string, double> counts;
  for (const prometheus::MetricFamily& family : registry.Collect()) {
    EXPECT_EQ(family.name, "dcs_test_refused_total");
    for (const prometheus::ClientMetric& metric : family.metric) {
      EXPECT_EQ(metric.label.size(), 1u);
      counts[metric.label.at(0).value] = metric.counter.value;
    }
  }
  return counts;
}

TEST(RefusalCounterTest, CommonReasonsStartAtZeroAndRefusalsCountByCode) {
  prometheus::Registry registry;
  RefusalCounter counter(registry, "dcs_test_refused_total", "Refusals.");
  const std::map<std::string, double> zero = {
      {"INVALID_ARGUMENT", 0}, {"NOT_FOUND", 0}, {"FAILED_PRECONDITION", 0}};
  EXPECT_EQ(ByReason(registry), zero);

  counter.Count(absl::OkStatus());
  counter.Count(absl::NotFoundError("no run-9"));
  counter.Count(absl::NotFoundError("no run-8"));
  counter.Count(absl::ResourceExhaustedError("full"));
  const std::map<std::string, double> counted = {{"INVALID_ARGUMENT", 0},
                                                 {"NOT_FOUND", 2},
                                                 {"FAILED_PRECONDITION", 0},
                                                 {"RESOURCE_EXHAUSTED", 1}};
  EXPECT_EQ(ByReason(registry), counted);
}

}  // namespace
}  // namespace dcs::services
