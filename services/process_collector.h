// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_PROCESS_COLLECTOR_H_
#define DCS_SERVICES_PROCESS_COLLECTOR_H_

// The standard process_* metrics (CPU seconds, resident and virtual memory, open and maximum
// file descriptors, threads, start time), read from /proc/self at every scrape. prometheus-cpp
// has no process collector of its own. Thread-safe.

#include <vector>

#include <prometheus/collectable.h>
#include <prometheus/metric_family.h>

namespace dcs::services {

class ProcessCollector final : public prometheus::Collectable {
 public:
  std::vector<prometheus::MetricFamily> Collect() const override;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_PROCESS_COLLECTOR_H_
