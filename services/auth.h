// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_AUTH_H_
#define DCS_SERVICES_AUTH_H_

// How the processes of a cluster know each other: a bearer token, and optionally mutual TLS.
//
// Token. Every process of a cluster holds the same token: a service requires it on every call
// of its own services (`authorization: Bearer <token>` in the call's metadata) and presents it
// on every channel it opens (services/channel.h), so the check holds between services as well
// as from `dcs`. Health (grpc.health.v1) and reflection stay open for probes. Without a token
// nothing is required or presented. Plaintext channels carry it in metadata: gRPC's call
// credentials refuse to travel without transport security.
//
// Mutual TLS. With certificate files, servers accept only TLS connections from clients whose
// certificate chains to the CA bundle, and clients accept only servers whose certificate does
// and names the address dialled, or the cluster's server name when one is set; every process
// presents its own certificate. gRPC's file watcher rereads the three files every few
// seconds, so renewed certificates take effect without a restart.
//
// Server name. In containers a learner is dialled at an address no certificate made in
// advance can name (a container's short id, a pod IP), so every server of a cluster may hold
// a certificate for one cluster-wide name (`server.dcs`) that clients check instead. That
// weakens nothing the cluster relies on: only the cluster's private CA issues such
// certificates, and every peer must present one (mutual TLS). Consul and Nomad do the same.
//
// Both are process-wide: set once at start-up, before any server starts or channel opens
// (services/service_main.cc, the `dcs` client's main); read-only afterwards, hence safe from
// any thread. Refused calls are counted by the servers' gRPC metrics
// (grpc_server_handled_total{grpc_code="UNAUTHENTICATED"}).

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace grpc {
class ChannelCredentials;
class ServerContextBase;
class ServerCredentials;
}  // namespace grpc

namespace dcs::services {

// The shortest token accepted: 128 bits, hex-encoded.
inline constexpr size_t kMinTokenLength = 32;

// The environment variable that holds the token itself (when no token file is given).
inline constexpr char kTokenEnvironmentVariable[] = "DCS_TOKEN";

// The token from `file` (its content, surrounding whitespace removed) if `file` is not empty,
// else from $DCS_TOKEN; "" when neither is set (no authentication). INVALID_ARGUMENT, naming
// the file or the variable, for an unreadable file, a token shorter than kMinTokenLength or
// one with characters other than printable ASCII.
absl::StatusOr<std::string> LoadToken(const std::string& file);

// A new token: 256 bits from OpenSSL's CSPRNG, hex-encoded.
std::string NewToken();

// Sets the process's token (see above). `token` must be "" or valid as LoadToken returns it.
void SetClusterToken(std::string token);
const std::string& ClusterToken();

// OK if the cluster has no token or the call presents it; else UNAUTHENTICATED saying whether
// the token was missing or wrong (never the token). Compares in constant time.
// Services call it in one place only, ServedCalls::Serve (services/served_calls.h).
absl::Status Authenticate(const grpc::ServerContextBase& context);

// Certificate files (PEM) for mutual TLS.
struct TlsFiles {
  std::string certificate;  // this process's certificate chain
  std::string key;          // its private key
  std::string ca;           // the CA bundle peers' certificates must chain to
  // The name every server's certificate must carry, checked by clients instead of the address
  // dialled; "" to check the address.
  std::string server_name;
  // Whether there are files, hence mutual TLS (a server name alone is refused).
  bool enabled() const { return !certificate.empty() || !key.empty() || !ca.empty(); }
};

// Adds --tls-cert, --tls-key, --tls-ca and --tls-server-name (each with a DCS_TLS_...
// environment fallback), bound to `files`.
void AddTlsFlags(CLI::App& app, TlsFiles& files);

// OK if none or all three files are given and each is a readable PEM file, and a server name
// only with the files; else INVALID_ARGUMENT naming the missing flag or the file and what is
// wrong with it.
absl::Status CheckTlsFiles(const TlsFiles& files);

// Sets the process's TLS files and server name (see above), none to go back to plaintext;
// `files` must have passed CheckTlsFiles.
void SetClusterTls(const TlsFiles& files);

// The server name clients check instead of the address dialled (services/channel.cc); "" to
// check the address, and always without TLS.
const std::string& ClusterTlsServerName();

// What servers listen with and channels dial with: mutual TLS over the cluster's files, or
// plaintext without them.
std::shared_ptr<grpc::ServerCredentials> ClusterServerCredentials();
std::shared_ptr<grpc::ChannelCredentials> ClusterChannelCredentials();

}  // namespace dcs::services

#endif  // DCS_SERVICES_AUTH_H_
