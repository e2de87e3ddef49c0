// Copyright 2026 The DCS Authors.
#include "services/process_collector.h"

#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace dcs::services {
namespace {

// The fields of /proc/self/stat that the metrics need (proc(5) numbering in comments).
struct ProcStat {
  double utime_ticks = 0;      // 14
  double stime_ticks = 0;      // 15
  double num_threads = 0;      // 20
  double starttime_ticks = 0;  // 22, since boot
  double vsize_bytes = 0;      // 23
  double rss_pages = 0;        // 24
};

bool ReadProcStat(ProcStat* stat) {
  std::ifstream file("/proc/self/stat");
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  // The command name (field 2) may contain spaces; fields after it are plain numbers.
  const size_t end_of_comm = text.rfind(')');
  if (end_of_comm == std::string::npos) return false;
  std::istringstream fields(text.substr(end_of_comm + 2));
  std::string field;
  for (int index = 3; fields >> field; ++index) {
    switch (index) {
      case 14: stat->utime_ticks = std::stod(field); break;
      case 15: stat->stime_ticks = std::stod(field); break;
      case 20: stat->num_threads = std::stod(field); break;
      case 22: stat->starttime_ticks = std::stod(field); break;
      case 23: stat->vsize_bytes = std::stod(field); break;
      case 24: stat->rss_pages = std::stod(field); return true;
      default: break;
    }
  }
  return false;
}

// Seconds since the epoch at which the machine booted ("btime" in /proc/stat).
double BootTimeSeconds() {
  std::ifstream file("/proc/stat");
  std::string key;
  double value = 0;
  while (file >> key) {
    if (key == "btime" && file >> value) return value;
    file.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return 0;
}

prometheus::MetricFamily Family(const char* name, const char* help, prometheus::MetricType type,
                                double value) {
  prometheus::ClientMetric metric;
  if (type == prometheus::MetricType::Counter) {
    metric.counter.value = value;
  } else {
    metric.gauge.value = value;
  }
  return prometheus::MetricFamily{name, help, type, {metric}};
}

}  // namespace

std::vector<prometheus::MetricFamily> ProcessCollector::Collect() const {
  using prometheus::MetricType;
  std::vector<prometheus::MetricFamily> families;
  ProcStat stat;
  if (ReadProcStat(&stat)) {
    const double ticks_per_second = static_cast<double>(sysconf(_SC_CLK_TCK));
    const double page_bytes = static_cast<double>(sysconf(_SC_PAGESIZE));
    families.push_back(Family("process_cpu_seconds_total",
                              "Total user and system CPU time spent in seconds.",
                              MetricType::Counter,
                              (stat.utime_ticks + stat.stime_ticks) / ticks_per_second));
    families.push_back(Family("process_resident_memory_bytes", "Resident memory size in bytes.",
                              MetricType::Gauge, stat.rss_pages * page_bytes));
    families.push_back(Family("process_virtual_memory_bytes", "Virtual memory size in bytes.",
                              MetricType::Gauge, stat.vsize_bytes));
    families.push_back(Family("process_threads", "Number of OS threads in the process.",
                              MetricType::Gauge, stat.num_threads));
    families.push_back(Family(
        "process_start_time_seconds", "Start time of the process since unix epoch in seconds.",
        MetricType::Gauge, BootTimeSeconds() + stat.starttime_ticks / ticks_per_second));
  }
  std::error_code error;
  double open_fds = 0;
  for (auto it = std::filesystem::directory_iterator("/proc/self/fd", error);
       !error && it != std::filesystem::directory_iterator(); it.increment(error)) {
    ++open_fds;
  }
  families.push_back(Family("process_open_fds", "Number of open file descriptors.",
                            MetricType::Gauge, open_fds));
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) == 0) {
    families.push_back(Family("process_max_fds", "Maximum number of open file descriptors.",
                              MetricType::Gauge, static_cast<double>(limit.rlim_cur)));
  }
  return families;
}

}  // namespace dcs::services
