// Copyright 2026 The DCS Authors.
#include "services/grpc_server_metrics.h"

#include <map>
#include <string>
#include <vector>

#include <prometheus/registry.h>

#include "grpc/health/v1/health.pb.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

// The value of the series of `family_name` whose labels are exactly `labels`; -1 if absent.
double Value(prometheus::Registry& registry, const std::string& family_name,
             const std::map<std::string, std::string>& labels) {
  for (const prometheus::MetricFamily& family : registry.Collect()) {
    if (family.name != family_name) continue;
    for (const prometheus::ClientMetric& metric : family.metric) {
      std::map<std::string, std::string> have;
      for (const auto& label : metric.label) have[label.name] = label.value;
      if (have != labels) continue;
      switch (family.type) {
        case prometheus::MetricType::Counter:
          return metric.counter.value;
        case prometheus::MetricType::Histogram:
          return static_cast<double>(metric.histogram.sample_count);
        default:
          return metric.gauge.value;
      }
    }
  }
  return -1;
}

TEST(GrpcServerMetricsTest, ParseCallSplitsServiceAndMethod) {
  const GrpcServerMetrics::Call call =
      GrpcServerMetrics::ParseCall("/dcs.v1.CoordinatorService/RegisterWorker", "unary");
  EXPECT_EQ(call.type, "unary");
  EXPECT_EQ(call.service, "dcs.v1.CoordinatorService");
  EXPECT_EQ(call.method, "RegisterWorker");
}

TEST(GrpcServerMetricsTest, ParseCallWithoutMethod) {
  const GrpcServerMetrics::Call call = GrpcServerMetrics::ParseCall("/justaservice", "unary");
  EXPECT_EQ(call.service, "justaservice");
  EXPECT_EQ(call.method, "");
}

TEST(GrpcServerMetricsTest, InitializeServiceCreatesZeroSeriesForEveryMethod) {
  // Links health.proto's descriptors into this binary (Server does the same).
  ASSERT_NE(grpc::health::v1::HealthCheckRequest::descriptor(), nullptr);
  prometheus::Registry registry;
  GrpcServerMetrics metrics(registry);
  metrics.InitializeService("grpc.health.v1.Health");
  const std::map<std::string, std::string> check = {
      {"grpc_type", "unary"}, {"grpc_service", "grpc.health.v1.Health"}, {"grpc_method", "Check"}};
  const std::map<std::string, std::string> watch = {{"grpc_type", "server_stream"},
                                                    {"grpc_service", "grpc.health.v1.Health"},
                                                    {"grpc_method", "Watch"}};
  EXPECT_EQ(Value(registry, "grpc_server_started_total", check), 0);
  EXPECT_EQ(Value(registry, "grpc_server_started_total", watch), 0);
  auto with_ok = [](std::map<std::string, std::string> labels) {
    labels["grpc_code"] = "OK";
    return labels;
  };
  EXPECT_EQ(Value(registry, "grpc_server_handled_total", with_ok(check)), 0);
  EXPECT_EQ(Value(registry, "grpc_server_handled_total", with_ok(watch)), 0);
}

TEST(GrpcServerMetricsTest, UnknownServiceIsIgnored) {
  prometheus::Registry registry;
  GrpcServerMetrics metrics(registry);
  metrics.InitializeService("no.such.Service");
  for (const prometheus::MetricFamily& family : registry.Collect()) {
    EXPECT_TRUE(family.metric.empty()) << family.name;
  }
}

TEST(GrpcServerMetricsTest, RecordsEventsOfACall) {
  prometheus::Registry registry;
  GrpcServerMetrics metrics(registry);
  const GrpcServerMetrics::Call call =
      GrpcServerMetrics::ParseCall("/dcs.v1.CoordinatorService/Heartbeat", "unary");
  metrics.RecordStarted(call);
  metrics.RecordMessageReceived(call);
  metrics.RecordMessageSent(call);
  metrics.RecordHandled(call, "NOT_FOUND", 0.003);
  metrics.RecordStarted(call);
  metrics.RecordHandled(call, "OK", 0.001);

  const std::map<std::string, std::string> labels = {{"grpc_type", "unary"},
                                                     {"grpc_service", "dcs.v1.CoordinatorService"},
                                                     {"grpc_method", "Heartbeat"}};
  auto with_code = [&](const std::string& code) {
    std::map<std::string, std::string> coded = labels;
    coded["grpc_code"] = code;
    return coded;
  };
  EXPECT_EQ(Value(registry, "grpc_server_started_total", labels), 2);
  EXPECT_EQ(Value(registry, "grpc_server_msg_received_total", labels), 1);
  EXPECT_EQ(Value(registry, "grpc_server_msg_sent_total", labels), 1);
  EXPECT_EQ(Value(registry, "grpc_server_handled_total", with_code("NOT_FOUND")), 1);
  EXPECT_EQ(Value(registry, "grpc_server_handled_total", with_code("OK")), 1);
  EXPECT_EQ(Value(registry, "grpc_server_handling_seconds", labels), 2);
}

}  // namespace
}  // namespace dcs::services
