// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_METRICS_ENDPOINT_H_
#define DCS_SERVICES_METRICS_ENDPOINT_H_

// A process's Prometheus endpoint: GET /metrics over HTTP. It always exports
//   dcs_build_info{component, version} 1
//   dcs_library_info{name, version} 1    (one per linked library; see common/library_version.h)
//   process_* (services/process_collector.h)
// and whatever the process registers in registry(). Thread-safe: prometheus-cpp metrics may be
// updated from any thread. Stops serving when destroyed.

#include <memory>
#include <string>
#include "absl/strings/string_view.h"
#include <vector>

#include <prometheus/registry.h>

#include "absl/status/statusor.h"
#include "services/build_info.h"

namespace prometheus {
class Exposer;
}

namespace dcs::services {

class MetricsEndpoint {
 public:
  // Serves on `listen_address` (host:port; port 0 picks a free port). UNAVAILABLE, naming the
  // address, if it cannot be bound.
  static absl::StatusOr<std::unique_ptr<MetricsEndpoint>> Start(absl::string_view listen_address,
                                                                absl::string_view component,
                                                                const BuildInfo& build);
  ~MetricsEndpoint();

  // The bound port.
  int port() const { return port_; }
  prometheus::Registry& registry() { return *registry_; }

  // Also serves what `collectable` reports at each scrape (metrics computed on demand).
  void AddCollectable(std::shared_ptr<prometheus::Collectable> collectable);

 private:
  MetricsEndpoint() = default;

  std::shared_ptr<prometheus::Registry> registry_;
  std::vector<std::shared_ptr<prometheus::Collectable>> collectables_;
  std::unique_ptr<prometheus::Exposer> exposer_;
  int port_ = 0;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_METRICS_ENDPOINT_H_
