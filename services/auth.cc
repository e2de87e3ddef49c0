// Copyright 2026 The DCS Authors.
#include "services/auth.h"

#include <grpcpp/server_context.h>
#include <openssl/crypto.h>
#include <openssl/rand.h>

#include <cstdlib>
#include <string>
#include <utility>

#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"

namespace dcs::services {
namespace {

constexpr absl::string_view kScheme = "Bearer ";

std::string& Token() {
  static auto* token = new std::string();  // never destroyed: read by threads until exit
  return *token;
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

}  // namespace dcs::services
