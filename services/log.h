// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_LOG_H_
#define DCS_SERVICES_LOG_H_

// Structured logging for DCS processes: one line per event on stderr, either human-readable
// text (`2026-11-21T09:30:00.123Z INFO coordinator: worker registered worker_id=actor-2`) or
// one JSON object per line for log collectors. Libraries do not log; they return statuses,
// and the process that handles an error logs it once.
//
// Thread-safe: each line is written with a single write(2). ConfigureLogging must run in main
// before other threads start.

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>
#include "absl/strings/string_view.h"

#include "absl/strings/str_cat.h"

namespace dcs::services {

enum class LogLevel { kDebug, kInfo, kWarning, kError };
enum class LogFormat { kText, kJson };

// The names flags and JSON lines use: "debug", "info", "warning", "error"; "text", "json".
std::vector<std::pair<std::string, LogLevel>> LogLevelNames();
std::vector<std::pair<std::string, LogFormat>> LogFormatNames();

struct LogOptions {
  std::string component;  // "coordinator", "learner", "actor", "dcs"
  LogLevel min_level = LogLevel::kInfo;
  LogFormat format = LogFormat::kText;
};

// Sets the process's logging options and routes gRPC's own log messages through Log (gRPC's
// errors at kWarning, the rest at kDebug).
void ConfigureLogging(const LogOptions& options);

// One key=value pair of a log line. Numbers and strings convert implicitly.
struct LogField {
  LogField(absl::string_view k, const absl::AlphaNum& v) : key(k), value(v.Piece()) {}
  absl::string_view key;
  std::string value;
};

void Log(LogLevel level, absl::string_view message, std::initializer_list<LogField> fields = {});

// While alive, gRPC's log messages are held here instead of being logged, so that a failure
// inside a gRPC call (a port in use) can be reported as one line with gRPC's reason in it.
// At most one at a time.
class GrpcLogCapture {
 public:
  GrpcLogCapture();
  ~GrpcLogCapture();
  GrpcLogCapture(const GrpcLogCapture&) = delete;
  GrpcLogCapture& operator=(const GrpcLogCapture&) = delete;

  // gRPC's error messages captured so far, joined by "; ".
  std::string errors() const;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_LOG_H_
