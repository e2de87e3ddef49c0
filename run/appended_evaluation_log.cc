// Copyright 2026 The DCS Authors.
#include "run/appended_evaluation_log.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <system_error>

#include <google/protobuf/util/json_util.h>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "dcs/proto_json.h"
#include "run/evaluation_log.h"

namespace dcs::run {
namespace {

namespace fs = std::filesystem;

constexpr char kLinesFile[] = "evaluations.jsonl";
constexpr char kSummaryFile[] = "evaluations.summary.json";

std::string PathIn(const std::string& dir, const char* file) {
  return (fs::path(dir) / file).string();
}

// `message` from the JSON `text`, read from `where`; DATA_LOSS naming it if that is not one.
absl::Status ParseJson(absl::string_view text, const std::string& where,
                       google::protobuf::Message& message) {
  const auto parsed = google::protobuf::util::JsonStringToMessage(
      google::protobuf::StringPiece(text.data(), text.size()), &message);
  if (parsed.ok()) return absl::OkStatus();
  return absl::DataLossError(absl::StrCat(where, " is not ", message.GetDescriptor()->name(),
                                          ": ", parsed.message().as_string()));
}

// The summary of the log in `dir`. NOT_FOUND if there is none.
absl::StatusOr<v1::AppendedEvaluationLog> ReadSummary(const std::string& dir) {
  const std::string path = PathIn(dir, kSummaryFile);
  absl::StatusOr<std::string> json = ReadFile(path);
  if (!json.ok()) {
    return absl::NotFoundError(absl::StrCat("no evaluation log in ", dir, ": ", path));
  }
  v1::AppendedEvaluationLog summary;
  DCS_RETURN_IF_ERROR(ParseJson(*json, path, summary));
  if (summary.evaluations() < 0 || summary.bytes() < 0) {
    return absl::DataLossError(absl::StrCat(path, " counts ", summary.evaluations(),
                                            " evaluations in ", summary.bytes(), " bytes"));
  }
  return summary;
}

// Cuts `path` (created if missing) to its first `length` bytes, which drops what a crash left
// after them, appends `lines` and fsyncs it. Its directory entry is made durable by the summary's
// atomic write into the same directory, which follows.
absl::Status AppendAt(const std::string& path, int64_t length, absl::string_view lines) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return FileError(errno, "cannot open", path);
  absl::Status status;
  if (::ftruncate(fd, length) != 0) status = FileError(errno, "cannot truncate", path);
  for (size_t written = 0; status.ok() && written < lines.size();) {
    const ssize_t n = ::pwrite(fd, lines.data() + written, lines.size() - written,
                               length + static_cast<int64_t>(written));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) status = FileError(errno, "cannot write", path);
    if (n > 0) written += static_cast<size_t>(n);
  }
  if (status.ok() && ::fsync(fd) != 0) status = FileError(errno, "cannot fsync", path);
  ::close(fd);
  return status;
}

// Appends `evaluations[from:]` to the log of `dir` whose summary is `summary`, then commits
// the log as `fields` (its evaluations ignored) with them.
absl::Status Append(const std::string& dir, v1::AppendedEvaluationLog summary,
                    const v1::EvaluationLog& fields,
                    const google::protobuf::RepeatedPtrField<v1::Evaluation>& evaluations,
                    int from) {
  std::string lines;
  for (int i = from; i < evaluations.size(); ++i) {
    absl::StrAppend(&lines, ProtoToJsonLine(evaluations[i]), "\n");
  }
  DCS_RETURN_IF_ERROR(AppendAt(PathIn(dir, kLinesFile), summary.bytes(), lines));
  *summary.mutable_summary() = fields;
  summary.mutable_summary()->clear_evaluations();
  summary.set_evaluations(summary.evaluations() + evaluations.size() - from);
  summary.set_bytes(summary.bytes() + static_cast<int64_t>(lines.size()));
  return WriteFileAtomically(PathIn(dir, kSummaryFile), ProtoToJson(summary));
}

// The summary of the log in `dir` to append to: an empty log if it has none; a log of
// WriteEvaluationLog's (from a coordinator before this form) rewritten in this form first.
absl::StatusOr<v1::AppendedEvaluationLog> SummaryToAppendTo(const std::string& dir) {
  absl::StatusOr<v1::AppendedEvaluationLog> summary = ReadSummary(dir);
  if (!absl::IsNotFound(summary.status())) return summary;
  absl::StatusOr<v1::EvaluationLog> written = ReadEvaluationLog(dir);
  if (absl::IsNotFound(written.status())) return v1::AppendedEvaluationLog();
  DCS_RETURN_IF_ERROR(written.status());
  DCS_RETURN_IF_ERROR(Append(dir, {}, *written, written->evaluations(), 0));
  // Readers take the appended log from now on; the files it came from would only mislead.
  for (const EvaluationLogFile& file : EvaluationLogFiles(*written)) {
    const std::string path = PathIn(dir, file.name.c_str());
    std::error_code error;
    fs::remove(path, error);
    if (error) return FileError(error.value(), "cannot remove", path);
  }
  return ReadSummary(dir);
}

}  // namespace

v1::EvaluationLog EvaluationLogSince(const v1::EvaluationLog& log, int64_t first) {
  v1::EvaluationLog since = log;
  since.mutable_evaluations()->DeleteSubrange(
      0, static_cast<int>(std::min<int64_t>(first, log.evaluations_size())));
  return since;
}

absl::Status AppendEvaluationLog(const std::string& dir, int64_t first,
                                 const v1::EvaluationLog& since) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) return FileError(error.value(), "cannot create", dir);
  DCS_ASSIGN_OR_RETURN(const v1::AppendedEvaluationLog summary, SummaryToAppendTo(dir));
  if (first > summary.evaluations()) {
    // Not FAILED_PRECONDITION: learners take that for a lost lease, and the run would go from
    // one to the next for ever.
    return absl::DataLossError(absl::StrCat(
        "the evaluation log in ", dir, " holds ", summary.evaluations(),
        " evaluations; evaluations from number ", first + 1, " on cannot follow them"));
  }
  // Those the log holds already, sent again.
  const int64_t held = summary.evaluations() - first;
  if (held > since.evaluations_size()) return absl::OkStatus();  // the log is ahead
  return Append(dir, summary, since, since.evaluations(), static_cast<int>(held));
}

bool HasAppendedEvaluationLog(const std::string& dir) {
  std::error_code error;
  return fs::exists(PathIn(dir, kSummaryFile), error);
}

absl::StatusOr<v1::EvaluationLog> ReadAppendedEvaluationLog(const std::string& dir) {
  DCS_ASSIGN_OR_RETURN(const v1::AppendedEvaluationLog summary, ReadSummary(dir));
  const std::string path = PathIn(dir, kLinesFile);
  std::string text;
  if (summary.bytes() > 0) {
    DCS_ASSIGN_OR_RETURN(text, ReadFile(path));
  }
  if (static_cast<int64_t>(text.size()) < summary.bytes()) {
    return absl::DataLossError(absl::StrCat(path, " holds ", text.size(), " bytes; its summary ",
                                            kSummaryFile, " says the log has ", summary.bytes()));
  }
  // What follows the log's bytes is a crash's unfinished append: not the log's.
  const absl::string_view lines = absl::string_view(text).substr(0, summary.bytes());
  v1::EvaluationLog log = summary.summary();
  size_t start = 0;
  while (start < lines.size()) {
    const size_t end = lines.find('\n', start);
    const std::string where = absl::StrCat(path, " line ", log.evaluations_size() + 1);
    if (end == absl::string_view::npos) {
      return absl::DataLossError(absl::StrCat(where, " is cut short"));
    }
    v1::Evaluation& evaluation = *log.add_evaluations();
    DCS_RETURN_IF_ERROR(ParseJson(lines.substr(start, end - start), where, evaluation));
    DCS_RETURN_IF_ERROR(internal::CheckSplits(evaluation, where));
    start = end + 1;
  }
  if (log.evaluations_size() != summary.evaluations()) {
    return absl::DataLossError(absl::StrCat(path, " holds ", log.evaluations_size(),
                                            " evaluations in ", summary.bytes(),
                                            " bytes; its summary says ", summary.evaluations()));
  }
  return log;
}

}  // namespace dcs::run
