// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CHANNEL_H_
#define DCS_SERVICES_CHANNEL_H_

// The client side of the wire: every DCS client opens its channels here, so keepalive and
// reconnect settings are the same everywhere. Thread-safe.

#include <memory>
#include <string>

#include "absl/time/time.h"

namespace grpc {
class Channel;
class ClientContext;
}  // namespace grpc

namespace dcs::services {

// The largest reply a client accepts: a 10,000-run sweep's results, with room.
inline constexpr int kMaxReceiveBytes = 256 << 20;

// A channel to `address` (host:port) that pings an idle peer every 30 s, so a dead peer behind
// NAT is noticed, reconnects at most 2 s apart, accepts replies up to kMaxReceiveBytes, and
// presents the cluster's token on every call, over mutual TLS when the cluster has
// certificates (services/auth.h).
std::shared_ptr<grpc::Channel> OpenChannel(const std::string& address);

// Sets `timeout` as the deadline of a call: every DCS client call has one.
void SetTimeout(grpc::ClientContext& context, absl::Duration timeout);

}  // namespace dcs::services

#endif  // DCS_SERVICES_CHANNEL_H_
