// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_INTEGRATION_TEST_UTIL_H_
#define DCS_TESTS_INTEGRATION_TEST_UTIL_H_

// Helpers for tests that run real DCS processes on loopback. Thread-compatible.
// Temporary directories, HTTP GETs and free ports are in tests/testing/.

#include <google/protobuf/struct.pb.h>

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "tests/testing/scoped_variable.h"

namespace dcs::integration {

// The directory holding this build's dcs, dcs-coordinator, dcs-learner and dcs-actor.
std::string BinDir();

// `name` in BinDir().
std::string BinaryPath(const std::string& name);

struct RunResult {
  int exit_code = -1;  // -1 if killed by a signal (or at the timeout)
  std::string output;  // stdout and stderr, interleaved as written
};

// Runs `path args...` to completion; kills it after `timeout` (stretched in a sanitized build:
// tests/testing/slowdown.h).
RunResult RunProgram(const std::string& path, const std::vector<std::string>& args,
              absl::Duration timeout = absl::Seconds(60));

// `dcs ARGS... --addr=ADDRESS`, killed after `timeout`.
RunResult DcsAt(std::vector<std::string> args, const std::string& address,
                absl::Duration timeout = absl::Minutes(1));

// The dynamic loader's report on every program the test starts while this lives (LD_DEBUG=libs,
// written to files of its own: LD_DEBUG_OUTPUT), to count how often libtorch starts in them.
// Sets those variables until destroyed: one at a time, on the test's thread.
class LoaderReport {
 public:
  LoaderReport();

  // How many times libtorch started so far: each program image that links it runs
  // libtorch_cpu's initialisers once, so a program that runs itself again counts twice.
  int LibtorchStarts() const;

 private:
  const std::string dir_;
  const testing::ScopedVariable debug_;
  const testing::ScopedVariable output_;
};

// The lines of `text`, without empty ones.
std::vector<std::string> Lines(const std::string& text);

// The value of the series `name{labels}` in a Prometheus exposition, or -1.
double MetricValue(const std::string& exposition, const std::string& series);

// `text` as JSON (an HTTP API's answer); INVALID_ARGUMENT with the parser's message if it is
// not JSON.
absl::StatusOr<google::protobuf::Value> ParseJsonValue(const std::string& text);

// The field `name` of the JSON object `object`; a null value if it has none or is no object.
const google::protobuf::Value& JsonField(const google::protobuf::Value& object,
                                         const std::string& name);

}  // namespace dcs::integration

#endif  // DCS_TESTS_INTEGRATION_TEST_UTIL_H_
