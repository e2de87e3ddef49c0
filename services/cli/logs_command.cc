// Copyright 2026 The DCS Authors.
#include "services/cli/logs_command.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "common/text_table.h"
#include "services/cli/local_cluster.h"
#include "services/did_you_mean.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

namespace fs = std::filesystem;

// How often -f looks for what the process wrote: as `tail -f` does, about.
constexpr absl::Duration kFollowInterval = absl::Milliseconds(200);

struct LogsFlags {
  std::string process;
  int lines = -1;  // all
  bool follow = false;
};

// The processes with a log in `data_dir`, sorted.
std::vector<std::string> LoggedProcesses(const std::string& data_dir) {
  std::vector<std::string> names;
  std::error_code error;
  for (const fs::directory_entry& entry :
       fs::directory_iterator(fs::path(data_dir) / "logs", error)) {
    if (entry.path().extension() == ".log") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

absl::Status NoLogs(const std::string& data_dir) {
  return absl::NotFoundError(
      absl::StrCat("no logs in ", data_dir, ": no cluster was started there (`dcs up`)"));
}

// The log of `process`, or NOT_FOUND naming the logs there and the closest name.
absl::StatusOr<std::string> LogOf(const std::string& data_dir, const std::string& process) {
  const std::vector<std::string> logged = LoggedProcesses(data_dir);
  if (std::find(logged.begin(), logged.end(), process) != logged.end()) {
    return ProcessLogPath(data_dir, process);
  }
  if (logged.empty()) return NoLogs(data_dir);
  const std::optional<std::string> closest = ClosestName(process, logged);
  return absl::NotFoundError(absl::StrCat(
      "no log of '", process, "' in ", data_dir, " (logs: ", absl::StrJoin(logged, ", "), ")",
      closest.has_value() ? absl::StrCat("; did you mean ", *closest, "?") : ""));
}

// Where the last `lines` lines of `text` start (0 for all of them, or for lines < 0).
size_t LastLinesStart(const std::string& text, int lines) {
  if (lines < 0) return 0;
  size_t start = text.size();
  // A final newline ends the last line; it does not start another.
  if (start > 0 && text[start - 1] == '\n') --start;
  for (int found = 0; start > 0; --start) {
    if (text[start - 1] == '\n' && ++found == lines) break;
  }
  return lines == 0 ? text.size() : start;
}

int ListLogs(const GlobalFlags& flags) {
  std::vector<std::vector<std::string>> rows = {{"PROCESS", "BYTES", "LOG"}};
  for (const std::string& process : LoggedProcesses(flags.data_dir)) {
    const std::string path = ProcessLogPath(flags.data_dir, process);
    std::error_code error;
    const uintmax_t bytes = fs::file_size(path, error);
    rows.push_back({process, error ? "?" : std::to_string(bytes), path});
  }
  if (rows.size() == 1) return FailCommand(NoLogs(flags.data_dir));
  std::cout << RenderTable(rows);
  return kExitOk;
}

int PrintLog(const GlobalFlags& flags, const LogsFlags& logs) {
  absl::StatusOr<std::string> path = LogOf(flags.data_dir, logs.process);
  if (!path.ok()) return FailCommand(path.status());
  absl::StatusOr<std::string> text = ReadFile(*path);
  if (!text.ok()) return FailCommand(text.status());
  std::cout << text->substr(LastLinesStart(*text, logs.lines)) << std::flush;
  uintmax_t printed = text->size();
  while (logs.follow) {  // until Ctrl-C
    absl::SleepFor(kFollowInterval);
    std::error_code error;
    const uintmax_t size = fs::file_size(*path, error);
    if (error) continue;  // between a new `dcs up`'s removal and its new log
    if (size < printed) printed = 0;  // a new cluster's log: from its start
    if (size == printed) continue;
    std::ifstream grown(*path, std::ios::binary);
    grown.seekg(static_cast<std::streamoff>(printed));
    const std::string more((std::istreambuf_iterator<char>(grown)),
                           std::istreambuf_iterator<char>());
    std::cout << more << std::flush;
    printed += more.size();
  }
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddLogsCommand(CLI::App& dcs, const GlobalFlags& flags) {
  auto logs_flags = std::make_shared<LogsFlags>();
  CLI::App* logs = dcs.add_subcommand(
      "logs", "Print a process's log of the local cluster in --data-dir (without PROCESS, list "
              "them); -f follows it");
  logs->add_option("process", logs_flags->process,
                   "coordinator, learner, actor-1, ... (as `dcs logs` lists them)");
  logs->add_option("-n,--lines", logs_flags->lines, "print only the last LINES lines")
      ->check(CLI::NonNegativeNumber);
  logs->add_flag("-f,--follow", logs_flags->follow,
                 "then print what the process writes, until Ctrl-C");
  return {{logs, [&flags, logs_flags] {
             if (logs_flags->process.empty()) {
               if (logs_flags->follow || logs_flags->lines >= 0) {
                 return FailCommand(UsageError("-n and -f need a PROCESS (see `dcs logs`)"));
               }
               return ListLogs(flags);
             }
             return PrintLog(flags, *logs_flags);
           }}};
}

}  // namespace dcs::services::cli
