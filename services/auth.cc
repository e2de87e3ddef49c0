// Copyright 2026 The DCS Authors.
#include "services/auth.h"

#include <grpcpp/security/credentials.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/security/tls_certificate_provider.h>
#include <grpcpp/security/tls_credentials_options.h>
#include <grpcpp/server_context.h>
#include <openssl/crypto.h>
#include <openssl/rand.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <tuple>
#include <utility>

#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"

namespace dcs::services {
namespace {

constexpr absl::string_view kScheme = "Bearer ";

// How often gRPC's file watcher rereads the certificate files.
constexpr unsigned kCertificateRefreshSeconds = 5;

std::string& Token() {
  static auto* token = new std::string();  // never destroyed: read by threads until exit
  return *token;
}

// The files' watcher, shared by every server and channel of the process (each watcher is a
// thread rereading the files); null without TLS.
std::shared_ptr<grpc::experimental::CertificateProviderInterface>& CertificateProvider() {
  static auto* provider =  // as Token()
      new std::shared_ptr<grpc::experimental::CertificateProviderInterface>();
  return *provider;
}

// What clients check servers' certificates against instead of the address dialled; "" for
// the address.
std::string& ServerName() {
  static auto* name = new std::string();  // as Token()
  return *name;
}

absl::StatusOr<std::string> CheckedToken(absl::string_view text, absl::string_view source) {
  const std::string token(absl::StripAsciiWhitespace(text));
  if (token.size() < kMinTokenLength) {
    return absl::InvalidArgumentError(
        absl::StrCat("the token in ", source, " is too short: ", token.size(),
                     " characters, at least ", kMinTokenLength, " needed"));
  }
  for (const char c : token) {
    if (c < '!' || c > '~') {
      return absl::InvalidArgumentError(
          absl::StrCat("the token in ", source, " has a character that is not printable ASCII"));
    }
  }
  return token;
}

}  // namespace

absl::StatusOr<std::string> LoadToken(const std::string& file) {
  if (!file.empty()) {
    absl::StatusOr<std::string> text = ReadFile(file);
    if (!text.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat("cannot read the token file: ", text.status().message()));
    }
    return CheckedToken(*text, file);
  }
  const char* variable = std::getenv(kTokenEnvironmentVariable);
  if (variable == nullptr || *variable == '\0') return "";
  return CheckedToken(variable, absl::StrCat("$", kTokenEnvironmentVariable));
}

std::string NewToken() {
  unsigned char bytes[32];
  // RAND_bytes fails only if OpenSSL cannot seed itself, which leaves nothing safe to do.
  if (RAND_bytes(bytes, sizeof(bytes)) != 1) std::abort();
  return absl::BytesToHexString(absl::string_view(reinterpret_cast<char*>(bytes), sizeof(bytes)));
}

void SetClusterToken(std::string token) { Token() = std::move(token); }

const std::string& ClusterToken() { return Token(); }

absl::Status Authenticate(const grpc::ServerContextBase& context) {
  const std::string& token = Token();
  if (token.empty()) return absl::OkStatus();
  const auto& metadata = context.client_metadata();
  const auto found = metadata.find("authorization");
  if (found == metadata.end()) {
    return absl::UnauthenticatedError("this cluster requires a token, and the call has none");
  }
  const absl::string_view presented(found->second.data(), found->second.size());
  const std::string expected = absl::StrCat(kScheme, token);
  if (presented.size() != expected.size() ||
      CRYPTO_memcmp(presented.data(), expected.data(), expected.size()) != 0) {
    return absl::UnauthenticatedError("the call's token is not this cluster's");
  }
  return absl::OkStatus();
}

void AddTlsFlags(CLI::App& app, TlsFiles& files) {
  app.add_option("--tls-cert", files.certificate,
                 "mutual TLS: this process's certificate chain (PEM; reread when it changes)")
      ->envname("DCS_TLS_CERT");
  app.add_option("--tls-key", files.key, "mutual TLS: its private key (PEM)")
      ->envname("DCS_TLS_KEY");
  app.add_option("--tls-ca", files.ca,
                 "mutual TLS: the CA bundle every peer's certificate must chain to (PEM)")
      ->envname("DCS_TLS_CA");
  app.add_option("--tls-server-name", files.server_name,
                 "mutual TLS: the name every server's certificate must carry, checked instead "
                 "of the address dialled (e.g. server.dcs, for servers in containers)")
      ->envname("DCS_TLS_SERVER_NAME");
}

absl::Status CheckTlsFiles(const TlsFiles& files) {
  if (!files.enabled()) {
    if (files.server_name.empty()) return absl::OkStatus();
    return absl::InvalidArgumentError(
        "--tls-server-name needs mutual TLS: --tls-cert, --tls-key and --tls-ca");
  }
  for (const auto& [path, flag, marker] :
       {std::tuple(files.certificate, "--tls-cert", "-----BEGIN CERTIFICATE-----"),
        std::tuple(files.key, "--tls-key", "PRIVATE KEY-----"),
        std::tuple(files.ca, "--tls-ca", "-----BEGIN CERTIFICATE-----")}) {
    if (path.empty()) {
      return absl::InvalidArgumentError(absl::StrCat(
          "mutual TLS needs --tls-cert, --tls-key and --tls-ca together; ", flag, " is missing"));
    }
    absl::StatusOr<std::string> pem = ReadFile(path);
    if (!pem.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat(flag, ": cannot read ", path, ": ", pem.status().message()));
    }
    if (!absl::StrContains(*pem, marker)) {
      return absl::InvalidArgumentError(absl::StrCat(flag, ": ", path, " holds no PEM ", marker));
    }
  }
  return absl::OkStatus();
}

void SetClusterTls(const TlsFiles& files) {
  CertificateProvider() =
      files.enabled() ? std::make_shared<grpc::experimental::FileWatcherCertificateProvider>(
                            files.key, files.certificate, files.ca, kCertificateRefreshSeconds)
                      : nullptr;
  ServerName() = files.enabled() ? files.server_name : "";
}

const std::string& ClusterTlsServerName() { return ServerName(); }

std::shared_ptr<grpc::ServerCredentials> ClusterServerCredentials() {
  if (CertificateProvider() == nullptr) return grpc::InsecureServerCredentials();
  grpc::experimental::TlsServerCredentialsOptions options(CertificateProvider());
  options.watch_root_certs();
  options.watch_identity_key_cert_pairs();
  options.set_cert_request_type(GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY);
  return grpc::experimental::TlsServerCredentials(options);
}

std::shared_ptr<grpc::ChannelCredentials> ClusterChannelCredentials() {
  if (CertificateProvider() == nullptr) return grpc::InsecureChannelCredentials();
  grpc::experimental::TlsChannelCredentialsOptions options;
  options.set_certificate_provider(CertificateProvider());
  options.watch_root_certs();
  options.watch_identity_key_cert_pairs();
  return grpc::experimental::TlsCredentials(options);
}

}  // namespace dcs::services
