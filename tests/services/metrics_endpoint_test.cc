// Copyright 2026 The DCS Authors.
#include "services/metrics_endpoint.h"

#include <memory>
#include <string>
#include <vector>

#include <prometheus/collectable.h>
#include <prometheus/counter.h>
#include <prometheus/metric_family.h>

#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/net.h"

namespace dcs::services {
namespace {

using dcs::testing::HttpGet;
using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// http://127.0.0.1:<port>/metrics
std::string MetricsUrl(int port) { return absl::StrCat("http://127.0.0.1:", port, "/metrics"); }

// Reports one gauge computed at each scrape, counting the scrapes.
class ScrapeCounter final : public prometheus::Collectable {
 public:
  std::vector<prometheus::MetricFamily> Collect() const override {
    prometheus::ClientMetric metric;
    metric.gauge.value = ++scrapes_;
    return {{"test_scrapes", "Scrapes seen.", prometheus::MetricType::Gauge, {metric}}};
  }

 private:
  mutable int scrapes_ = 0;
};

const BuildInfo kBuild = {.version = "9.8.7+t3st",
                          .libraries = {{"grpc", "1.51.1"}, {"sqlite", "3.40.1"}}};

TEST(MetricsEndpointTest, ServesBuildLibraryAndProcessMetrics) {
  absl::StatusOr<std::unique_ptr<MetricsEndpoint>> endpoint =
      MetricsEndpoint::Start("127.0.0.1:0", "coordinator", kBuild);
  ASSERT_TRUE(endpoint.ok()) << endpoint.status();
  ASSERT_GT((*endpoint)->port(), 0);
  std::string headers;
  const absl::StatusOr<std::string> response = HttpGet(MetricsUrl((*endpoint)->port()), &headers);
  EXPECT_THAT(headers, StartsWith("HTTP/1.1 200"));
  ASSERT_TRUE(response.ok()) << response.status();
  EXPECT_THAT(*response,
              ContainsRegex("dcs_build_info\\{(component=\"coordinator\",version=\"9\\.8\\.7\\+"
                            "t3st\"|version=\"9\\.8\\.7\\+t3st\",component=\"coordinator\")\\} 1"));
  EXPECT_THAT(*response,
              ContainsRegex("dcs_library_info\\{name=\"grpc\",version=\"1\\.51\\.1\"\\} 1"));
  EXPECT_THAT(*response,
              ContainsRegex("dcs_library_info\\{name=\"sqlite\",version=\"3\\.40\\.1\"\\} 1"));
  EXPECT_THAT(*response, HasSubstr("\nprocess_resident_memory_bytes "));
  EXPECT_THAT(*response, HasSubstr("\nprocess_open_fds "));
  EXPECT_THAT(*response, HasSubstr("# TYPE process_cpu_seconds_total counter"));
}

TEST(MetricsEndpointTest, ServesWhatTheProcessRegisters) {
  absl::StatusOr<std::unique_ptr<MetricsEndpoint>> started =
      MetricsEndpoint::Start("127.0.0.1:0", "actor", kBuild);
  ASSERT_TRUE(started.ok()) << started.status();
  MetricsEndpoint& endpoint = **started;
  prometheus::BuildCounter()
      .Name("test_events_total")
      .Help("Events.")
      .Register(endpoint.registry())
      .Add({{"kind", "x"}})
      .Increment(3);
  endpoint.AddCollectable(std::make_shared<ScrapeCounter>());

  const absl::StatusOr<std::string> first = HttpGet(MetricsUrl(endpoint.port()));
  ASSERT_TRUE(first.ok()) << first.status();
  EXPECT_THAT(*first, HasSubstr("test_events_total{kind=\"x\"} 3"));
  EXPECT_THAT(*first, HasSubstr("\ntest_scrapes 1"));
  // Computed again at every scrape.
  const absl::StatusOr<std::string> second = HttpGet(MetricsUrl(endpoint.port()));
  ASSERT_TRUE(second.ok()) << second.status();
  EXPECT_THAT(*second, HasSubstr("\ntest_scrapes 2"));
}

TEST(MetricsEndpointTest, PortInUseIsUnavailableNamingTheAddress) {
  absl::StatusOr<std::unique_ptr<MetricsEndpoint>> first =
      MetricsEndpoint::Start("127.0.0.1:0", "coordinator", kBuild);
  ASSERT_TRUE(first.ok()) << first.status();
  const std::string address = absl::StrCat("127.0.0.1:", (*first)->port());
  const absl::StatusOr<std::unique_ptr<MetricsEndpoint>> second =
      MetricsEndpoint::Start(address, "coordinator", kBuild);
  EXPECT_EQ(second.status().code(), absl::StatusCode::kUnavailable) << second.status();
  EXPECT_THAT(second.status().message(), HasSubstr(address));
  EXPECT_THAT(second.status().message(), HasSubstr("in use"));
  // The first endpoint still serves.
  const absl::StatusOr<std::string> scraped = HttpGet(MetricsUrl((*first)->port()));
  ASSERT_TRUE(scraped.ok()) << scraped.status();
  EXPECT_THAT(*scraped, HasSubstr("dcs_build_info"));
}

TEST(MetricsEndpointTest, StopsServingWhenDestroyed) {
  int port = 0;
  {
    absl::StatusOr<std::unique_ptr<MetricsEndpoint>> endpoint =
        MetricsEndpoint::Start("127.0.0.1:0", "learner", kBuild);
    ASSERT_TRUE(endpoint.ok()) << endpoint.status();
    port = (*endpoint)->port();
    const absl::StatusOr<std::string> scraped = HttpGet(MetricsUrl(port));
    ASSERT_TRUE(scraped.ok()) << scraped.status();
    ASSERT_THAT(*scraped, HasSubstr("dcs_build_info"));
  }
  // No response at all: not even a status line.
  std::string headers;
  const absl::StatusOr<std::string> after = HttpGet(MetricsUrl(port), &headers);
  EXPECT_FALSE(after.ok());
  EXPECT_EQ(headers, "");
}

}  // namespace
}  // namespace dcs::services
