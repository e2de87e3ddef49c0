// Copyright 2026 The DCS Authors.
#include "services/metrics_endpoint.h"

#include <httplib.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>

#include <prometheus/gauge.h>
#include <prometheus/text_serializer.h>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "services/process_collector.h"

namespace dcs::services {
namespace {

struct HostPort {
  std::string host;
  int port = 0;
};

// "host:port", "[v6 host]:port"; port 0 asks for a free one.
absl::StatusOr<HostPort> ParseListenAddress(absl::string_view listen_address) {
  const size_t colon = listen_address.rfind(':');
  HostPort parsed;
  if (colon == absl::string_view::npos ||
      !absl::SimpleAtoi(listen_address.substr(colon + 1), &parsed.port) || parsed.port < 0 ||
      parsed.port > 65535) {
    return absl::InvalidArgumentError(
        absl::StrCat("cannot serve metrics on ", listen_address, ": expected host:port"));
  }
  absl::string_view host = listen_address.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  parsed.host = std::string(host);
  return parsed;
}

// cpp-httplib does not say why a bind failed; binding the same address again does.
std::string BindFailureReason(const HostPort& address) {
  addrinfo hints{};
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE;
  addrinfo* addresses = nullptr;
  const std::string port = std::to_string(address.port);
  if (const int error = getaddrinfo(address.host.c_str(), port.c_str(), &hints, &addresses);
      error != 0) {
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
  absl::StatusOr<HostPort> address = ParseListenAddress(listen_address);
  if (!address.ok()) return address.status();
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
  endpoint->AddCollectable(endpoint->registry_);
  endpoint->AddCollectable(std::make_shared<ProcessCollector>());

  auto server = std::make_unique<httplib::Server>();
  // Two connections at once (Prometheus and a person's curl), each closed after its response,
  // so that no idle keep-alive connection holds a thread.
  server->new_task_queue = [] { return new httplib::ThreadPool(2); };
  server->set_keep_alive_max_count(1);
  // SO_REUSEADDR only: cpp-httplib's default adds SO_REUSEPORT, with which a second process
  // would share a port in use instead of being refused it.
  server->set_socket_options([](int socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  MetricsEndpoint* self = endpoint.get();
  server->Get("/metrics", [self](const httplib::Request&, httplib::Response& response) {
    response.set_content(self->Scrape(), "text/plain; version=0.0.4; charset=utf-8");
  });
  endpoint->port_ = address->port == 0
                        ? server->bind_to_any_port(address->host)
                        : (server->bind_to_port(address->host, address->port) ? address->port : -1);
  if (endpoint->port_ < 0) {
    return absl::UnavailableError(absl::StrCat("cannot serve metrics on ", listen_address, ": ",
                                               BindFailureReason(*address)));
  }
  endpoint->serving_ = std::thread([server = server.get()] { server->listen_after_bind(); });
  // stop() is a no-op until the server is running, and then the serving thread would never end.
  while (!server->is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  endpoint->server_ = std::move(server);
  return endpoint;
}

MetricsEndpoint::~MetricsEndpoint() {
  if (server_ == nullptr) return;
  server_->stop();
  serving_.join();
}

void MetricsEndpoint::AddCollectable(std::shared_ptr<prometheus::Collectable> collectable) {
  absl::MutexLock lock(&mutex_);
  collectables_.push_back(std::move(collectable));
}

std::string MetricsEndpoint::Scrape() const {
  std::vector<prometheus::MetricFamily> families;
  {
    absl::MutexLock lock(&mutex_);
    for (const auto& collectable : collectables_) {
      std::vector<prometheus::MetricFamily> collected = collectable->Collect();
      families.insert(families.end(), std::make_move_iterator(collected.begin()),
                      std::make_move_iterator(collected.end()));
    }
  }
  std::ostringstream text;
  prometheus::TextSerializer().Serialize(text, families);
  return text.str();
}

}  // namespace dcs::services
