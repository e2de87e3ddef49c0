// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_ADDRESS_H_
#define DCS_SERVICES_ADDRESS_H_

// "host:port" network addresses, as flags and the wire spell them ("127.0.0.1:50051",
// "[::1]:0", "coordinator:50051"). Thread-safe (pure functions).

#include <string>

#include "absl/strings/string_view.h"

namespace dcs::services {

// The host part: "[::1]:0" -> "[::1]". The whole text if it has no port.
std::string HostOf(absl::string_view address);

// The same host with another port: ("127.0.0.1:0", 41234) -> "127.0.0.1:41234".
std::string WithPort(absl::string_view address, int port);

// `host` and `port` as an address, a bare IPv6 host bracketed: ("fd00::1", 50052) ->
// "[fd00::1]:50052" (a pod IP as Kubernetes gives it); ("learner-0", 50052) -> "learner-0:50052".
std::string JoinHostPort(absl::string_view host, int port);

}  // namespace dcs::services

#endif  // DCS_SERVICES_ADDRESS_H_
