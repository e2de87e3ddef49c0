// Copyright 2026 The DCS Authors.
#include "services/process_collector.h"

#include <fcntl.h>
#include <unistd.h>

#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include <prometheus/metric_family.h>

#include "gtest/gtest.h"

namespace dcs::services {
namespace {

const prometheus::MetricFamily* Find(const std::vector<prometheus::MetricFamily>& families,
                                     const std::string& name) {
  for (const prometheus::MetricFamily& family : families) {
    if (family.name == name) return &family;
  }
  return nullptr;
}

// The single value of a gauge family, or nullopt if absent or not a one-sample gauge.
std::optional<double> GaugeValue(const std::vector<prometheus::MetricFamily>& families,
                                 const std::string& name) {
  const prometheus::MetricFamily* family = Find(families, name);
  if (family == nullptr || family->type != prometheus::MetricType::Gauge ||
      family->metric.size() != 1) {
    return std::nullopt;
  }
  return family->metric[0].gauge.value;
}

TEST(ProcessCollectorTest, CpuSecondsIsACounter) {
  const std::vector<prometheus::MetricFamily> families = ProcessCollector().Collect();
  const prometheus::MetricFamily* cpu = Find(families, "process_cpu_seconds_total");
  ASSERT_NE(cpu, nullptr);
  EXPECT_EQ(cpu->type, prometheus::MetricType::Counter);
  ASSERT_EQ(cpu->metric.size(), 1u);
  EXPECT_GE(cpu->metric[0].counter.value, 0.0);
  EXPECT_FALSE(cpu->help.empty());
}

TEST(ProcessCollectorTest, CpuSecondsGrowsWithWork) {
  ProcessCollector collector;
  const double before =
      Find(collector.Collect(), "process_cpu_seconds_total")->metric[0].counter.value;
  // Burn CPU until the clock ticks (at most a few hundred ms at 100 ticks per second).
  volatile double sink = 0;
  double after = before;
  for (int round = 0; round < 10000 && after <= before; ++round) {
    for (int i = 0; i < 100000; ++i) sink = sink + i * 0.5;
    after = Find(collector.Collect(), "process_cpu_seconds_total")->metric[0].counter.value;
  }
  EXPECT_GT(after, before);
}

TEST(ProcessCollectorTest, MemoryAndThreads) {
  const std::vector<prometheus::MetricFamily> families = ProcessCollector().Collect();
  const std::optional<double> resident = GaugeValue(families, "process_resident_memory_bytes");
  const std::optional<double> virtual_bytes = GaugeValue(families, "process_virtual_memory_bytes");
  const std::optional<double> threads = GaugeValue(families, "process_threads");
  ASSERT_TRUE(resident.has_value());
  ASSERT_TRUE(virtual_bytes.has_value());
  ASSERT_TRUE(threads.has_value());
  EXPECT_GT(*resident, 0);
  // Resident memory is a multiple of the page size and below the virtual size.
  EXPECT_EQ(static_cast<int64_t>(*resident) % sysconf(_SC_PAGESIZE), 0);
  EXPECT_GE(*virtual_bytes, *resident);
  EXPECT_GE(*threads, 1);
}

TEST(ProcessCollectorTest, StartTimeIsWithinTheLastDay) {
  const std::optional<double> start =
      GaugeValue(ProcessCollector().Collect(), "process_start_time_seconds");
  ASSERT_TRUE(start.has_value());
  const double now = static_cast<double>(std::time(nullptr));
  // Ticks are 10 ms; allow a second for rounding.
  EXPECT_LE(*start, now + 1);
  EXPECT_GT(*start, now - 24 * 3600);
}

TEST(ProcessCollectorTest, OpenFdsFollowsOpenFiles) {
  ProcessCollector collector;
  const std::optional<double> before = GaugeValue(collector.Collect(), "process_open_fds");
  ASSERT_TRUE(before.has_value());
  EXPECT_GE(*before, 3);  // stdin, stdout, stderr

  std::vector<int> fds;
  for (int i = 0; i < 5; ++i) fds.push_back(::open("/dev/null", O_RDONLY | O_CLOEXEC));
  const std::optional<double> during = GaugeValue(collector.Collect(), "process_open_fds");
  for (int fd : fds) ::close(fd);
  ASSERT_TRUE(during.has_value());
  EXPECT_EQ(*during, *before + 5);
}

TEST(ProcessCollectorTest, MaxFdsIsTheSoftLimit) {
  const std::optional<double> max_fds = GaugeValue(ProcessCollector().Collect(), "process_max_fds");
  ASSERT_TRUE(max_fds.has_value());
  EXPECT_GT(*max_fds, 0);
  EXPECT_EQ(*max_fds, static_cast<double>(sysconf(_SC_OPEN_MAX)));
}

}  // namespace
}  // namespace dcs::services
