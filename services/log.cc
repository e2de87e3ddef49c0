// Copyright 2026 The DCS Authors.
#include "services/log.h"

#include <grpc/support/log.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_join.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"

namespace dcs::services {
namespace {

LogOptions& Options() {
  static LogOptions* options = new LogOptions();
  return *options;
}

// Indexed by LogLevel.
constexpr std::array<absl::string_view, 4> kLevelNames = {"debug", "info", "warning", "error"};

absl::string_view LevelName(LogLevel level) { return kLevelNames[static_cast<size_t>(level)]; }

// Escapes quotes, backslashes and control characters, so an event stays on one line.
void AppendEscaped(std::string* out, absl::string_view text) {
  for (char c : text) {
    switch (c) {
      case '"': out->append("\\\""); break;
      case '\\': out->append("\\\\"); break;
      case '\n': out->append("\\n"); break;
      case '\r': out->append("\\r"); break;
      case '\t': out->append("\\t"); break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          absl::StrAppend(out, "\\u00", absl::Hex(static_cast<unsigned char>(c), absl::kZeroPad2));
        } else {
          out->push_back(c);
        }
    }
  }
}

void AppendJsonString(std::string* out, absl::string_view text) {
  out->push_back('"');
  AppendEscaped(out, text);
  out->push_back('"');
}

// A text value is quoted when it would not read back as one token.
void AppendTextValue(std::string* out, absl::string_view value) {
  const bool needs_quotes = value.empty() || std::any_of(value.begin(), value.end(), [](char c) {
                             return c == ' ' || c == '"' || c == '=' || c == '\\' ||
                                    static_cast<unsigned char>(c) < 0x20;
                           });
  if (needs_quotes) {
    AppendJsonString(out, value);
  } else {
    out->append(value.data(), value.size());
  }
}

// State of the (at most one) GrpcLogCapture.
absl::Mutex capture_mu(absl::kConstInit);
bool capturing ABSL_GUARDED_BY(capture_mu) = false;
std::vector<std::string>* captured_errors ABSL_GUARDED_BY(capture_mu) = nullptr;

void ForwardGrpcLog(gpr_log_func_args* args) {
  const bool is_error = args->severity == GPR_LOG_SEVERITY_ERROR;
  {
    absl::MutexLock lock(&capture_mu);
    if (capturing) {
      if (is_error) captured_errors->emplace_back(args->message);
      return;
    }
  }
  Log(is_error ? LogLevel::kWarning : LogLevel::kDebug, args->message,
      {{"source", "grpc"}, {"file", absl::StrCat(args->file, ":", args->line)}});
}

}  // namespace

std::vector<std::pair<std::string, LogLevel>> LogLevelNames() {
  std::vector<std::pair<std::string, LogLevel>> names;
  for (LogLevel level : {LogLevel::kDebug, LogLevel::kInfo, LogLevel::kWarning, LogLevel::kError}) {
    names.emplace_back(LevelName(level), level);
  }
  return names;
}

std::vector<std::pair<std::string, LogFormat>> LogFormatNames() {
  return {{"text", LogFormat::kText}, {"json", LogFormat::kJson}};
}

void ConfigureLogging(const LogOptions& options) {
  Options() = options;
  gpr_set_log_verbosity(options.min_level == LogLevel::kDebug ? GPR_LOG_SEVERITY_DEBUG
                                                               : GPR_LOG_SEVERITY_ERROR);
  gpr_set_log_function(ForwardGrpcLog);
}

void Log(LogLevel level, absl::string_view message, std::initializer_list<LogField> fields) {
  const LogOptions& options = Options();
  if (level < options.min_level) return;
  const std::string time =
      absl::FormatTime("%Y-%m-%dT%H:%M:%E3SZ", absl::Now(), absl::UTCTimeZone());
  std::string line;
  if (options.format == LogFormat::kJson) {
    absl::StrAppend(&line, "{\"time\":\"", time, "\",\"level\":\"", LevelName(level),
                    "\",\"component\":");
    AppendJsonString(&line, options.component);
    line.append(",\"msg\":");
    AppendJsonString(&line, message);
    for (const LogField& field : fields) {
      line.push_back(',');
      AppendJsonString(&line, field.key);
      line.push_back(':');
      AppendJsonString(&line, field.value);
    }
    line.append("}\n");
  } else {
    absl::StrAppend(&line, time, " ", absl::AsciiStrToUpper(LevelName(level)), " ",
                    options.component, ": ");
    AppendEscaped(&line, message);
    for (const LogField& field : fields) {
      absl::StrAppend(&line, " ", field.key, "=");
      AppendTextValue(&line, field.value);
    }
    line.push_back('\n');
  }
  // One write per line keeps lines from different threads whole.
  [[maybe_unused]] ssize_t written = ::write(STDERR_FILENO, line.data(), line.size());
}

GrpcLogCapture::GrpcLogCapture() {
  gpr_set_log_function(ForwardGrpcLog);  // in case ConfigureLogging has not run
  absl::MutexLock lock(&capture_mu);
  capturing = true;
  captured_errors = new std::vector<std::string>();
}

GrpcLogCapture::~GrpcLogCapture() {
  absl::MutexLock lock(&capture_mu);
  capturing = false;
  delete captured_errors;
  captured_errors = nullptr;
}

std::string GrpcLogCapture::errors() const {
  absl::MutexLock lock(&capture_mu);
  return absl::StrJoin(*captured_errors, "; ");
}

}  // namespace dcs::services
