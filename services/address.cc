// Copyright 2026 The DCS Authors.
#include "services/address.h"

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"

namespace dcs::services {

std::string HostOf(absl::string_view address) {
  // The last colon: an IPv6 host is bracketed, so its colons come before the port's.
  return std::string(address.substr(0, address.rfind(':')));
}

std::string WithPort(absl::string_view address, int port) {
  return JoinHostPort(HostOf(address), port);
}

std::string JoinHostPort(absl::string_view host, int port) {
  const bool bare_ipv6 = absl::StrContains(host, ':') && !absl::StartsWith(host, "[");
  return bare_ipv6 ? absl::StrCat("[", host, "]:", port) : absl::StrCat(host, ":", port);
}

}  // namespace dcs::services
