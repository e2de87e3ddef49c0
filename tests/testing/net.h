// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_TESTING_NET_H_
#define DCS_TESTS_TESTING_NET_H_

// Loopback networking for tests: ports that refuse connections, free ports, and HTTP GETs of
// the endpoints under test. Thread-compatible.

#include <string>

#include "absl/status/statusor.h"

namespace dcs::testing {

// A TCP port on 127.0.0.1 that is bound but not listening: connections to it are refused.
// port() is 0 if it could not be bound.
class RefusingPort {
 public:
  RefusingPort();
  ~RefusingPort();

  RefusingPort(const RefusingPort&) = delete;
  RefusingPort& operator=(const RefusingPort&) = delete;

  std::string address() const;  // "127.0.0.1:<port>"
  int port() const { return port_; }

 private:
  int fd_ = -1;
  int port_ = 0;
};

// A TCP port on 127.0.0.1 that was free a moment ago.
int PickFreePort();

// The body of an HTTP GET (libcurl). UNAVAILABLE if the request fails or is not 200.
// If `headers` is not null, it receives the status line and headers as received, even on
// failure ("" if no response arrived).
absl::StatusOr<std::string> HttpGet(const std::string& url, std::string* headers = nullptr);

// `text` percent-encoded for a URL's query string (libcurl's curl_easy_escape).
std::string UrlEncode(const std::string& text);

}  // namespace dcs::testing

#endif  // DCS_TESTS_TESTING_NET_H_
