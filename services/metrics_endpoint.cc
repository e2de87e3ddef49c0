// Copyright 2026 The DCS Authors.
#include "services/metrics_endpoint.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <exception>

#include <prometheus/exposer.h>
#include <prometheus/gauge.h>

#include "absl/strings/str_cat.h"
#include "services/process_collector.h"

namespace dcs::services {
namespace {

// civetweb does not say why a bind failed; binding the same address again does.
std::string BindFailureReason(absl::string_view listen_address) {
  const size_t colon = listen_address.rfind(':');
  if (colon == absl::string_view::npos) return "expected host:port";
  const std::string host(listen_address.substr(0, colon));
  const std::string port(listen_address.substr(colon + 1));
  addrinfo hints{};
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE;
  addrinfo* addresses = nullptr;
  if (const int error = getaddrinfo(host.c_str(), port.c_str(), &hints, &addresses); error != 0) {
    return gai_strerror(error);
  }
  std::string reason = "the address is not available on this host";
  const int fd = socket(addresses->ai_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd >= 0 && bind(fd, addresses->ai_addr, addresses->ai_addrlen) != 0) {
    reason = std::strerror(errno);
  }
  if (fd >= 0) close(fd);
  freeaddrinfo(addresses);
  return reason;
}

}  // namespace

absl::StatusOr<std::unique_ptr<MetricsEndpoint>> MetricsEndpoint::Start(
    absl::string_view listen_address, absl::string_view component, const BuildInfo& build) {
  std::unique_ptr<MetricsEndpoint> endpoint(new MetricsEndpoint());
  endpoint->registry_ = std::make_shared<prometheus::Registry>();
  prometheus::Registry& registry = *endpoint->registry_;

  prometheus::BuildGauge()
      .Name("dcs_build_info")
      .Help("The DCS build of this process; always 1.")
      .Register(registry)
      .Add({{"component", std::string(component)}, {"version", build.version}})
      .Set(1);
  auto& libraries = prometheus::BuildGauge()
                        .Name("dcs_library_info")
                        .Help("A third-party library linked into this process; always 1.")
                        .Register(registry);
  for (const LibraryVersion& library : build.libraries) {
    libraries.Add({{"name", library.name}, {"version", library.version}}).Set(1);
  }

  // civetweb reports a failed bind by throwing from the Exposer's constructor.
  try {
    endpoint->exposer_ =
        std::make_unique<prometheus::Exposer>(std::string(listen_address), /*num_threads=*/1);
  } catch (const std::exception&) {
    return absl::UnavailableError(absl::StrCat("cannot serve metrics on ", listen_address, ": ",
                                               BindFailureReason(listen_address)));
  }
  endpoint->exposer_->RegisterCollectable(endpoint->registry_);
  endpoint->AddCollectable(std::make_shared<ProcessCollector>());
  endpoint->port_ = endpoint->exposer_->GetListeningPorts().at(0);
  return endpoint;
}

MetricsEndpoint::~MetricsEndpoint() = default;

void MetricsEndpoint::AddCollectable(std::shared_ptr<prometheus::Collectable> collectable) {
  exposer_->RegisterCollectable(collectable);
  collectables_.push_back(std::move(collectable));
}

}  // namespace dcs::services
