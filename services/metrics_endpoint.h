// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_METRICS_ENDPOINT_H_
#define DCS_SERVICES_METRICS_ENDPOINT_H_

// A process's Prometheus endpoint: GET /metrics over HTTP. It always exports
//   dcs_build_info{component, version} 1
//   dcs_library_info{name, version} 1    (one per linked library; see common/library_version.h)
//   process_* (services/process_collector.h)
// and whatever the process registers in registry(). Thread-safe: prometheus-cpp metrics may be
// updated, and collectables added, from any thread while it serves. Stops serving when
// destroyed.
//
// prometheus-cpp collects and serializes; cpp-httplib serves, on one thread of its own.
// (prometheus-cpp's own Exposer serves through civetweb, whose worker threads Debian builds with
// 100 KiB stacks: too small for the static TLS of a process that links libtorch and the
// pthread OpenBLAS, so pthread_create fails with EINVAL and the Exposer never starts.)

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <prometheus/registry.h>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "services/build_info.h"

namespace httplib {
class Server;
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

  // The exposition text of every collectable, as of now.
  std::string Scrape() const;

  std::shared_ptr<prometheus::Registry> registry_;
  mutable absl::Mutex mutex_;
  std::vector<std::shared_ptr<prometheus::Collectable>> collectables_ ABSL_GUARDED_BY(mutex_);
  std::unique_ptr<httplib::Server> server_;
  std::thread serving_;
  int port_ = 0;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_METRICS_ENDPOINT_H_
