// Copyright 2026 The DCS Authors.
#include "tests/integration/test_util.h"

#include <sys/wait.h>

#include <filesystem>

#include <google/protobuf/util/json_util.h>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "services/cli/child_process.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {

std::string BinDir() { return DCS_BIN_DIR; }

std::string BinaryPath(const std::string& name) { return absl::StrCat(BinDir(), "/", name); }

RunResult RunProgram(const std::string& path, const std::vector<std::string>& args,
              absl::Duration timeout) {
  const std::string output_path = absl::StrCat(dcs::testing::MakeTempDir(), "/output");
  absl::StatusOr<services::cli::ChildProcess> child =
      services::cli::ChildProcess::Start({.path = path, .args = args, .output_path = output_path});
  if (!child.ok()) return {.exit_code = -1, .output = child.status().ToString()};
  std::optional<int> status = child->Wait(dcs::testing::Patient(timeout));
  const int wait_status = status ? *status : child->Stop(absl::ZeroDuration());
  RunResult result;
  result.exit_code = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  result.output = ReadFile(output_path).value_or("");
  return result;
}

RunResult DcsAt(std::vector<std::string> args, const std::string& address,
                absl::Duration timeout) {
  args.push_back("--addr=" + address);
  return RunProgram(BinaryPath("dcs"), args, timeout);
}

LoaderReport::LoaderReport()
    : dir_(dcs::testing::MakeTempDir()),
      debug_("LD_DEBUG", "libs"),
      // The loader appends ".<pid>" and keeps appending across exec: one file per process.
      output_("LD_DEBUG_OUTPUT", absl::StrCat(dir_, "/loader")) {}

int LoaderReport::LibtorchStarts() const {
  int starts = 0;
  for (const std::filesystem::directory_entry& file : std::filesystem::directory_iterator(dir_)) {
    const std::string report = ReadFile(file.path()).value_or("");
    for (absl::string_view line : absl::StrSplit(report, '\n')) {
      if (absl::StrContains(line, "calling init: ") &&
          absl::StrContains(line, "/libtorch_cpu.so")) {
        ++starts;
      }
    }
  }
  return starts;
}

std::vector<std::string> Lines(const std::string& text) {
  return absl::StrSplit(text, '\n', absl::SkipEmpty());
}

double MetricValue(const std::string& exposition, const std::string& series) {
  for (const std::string& line : Lines(exposition)) {
    if (absl::StartsWith(line, series + " ")) {
      double value = -1;
      return absl::SimpleAtod(line.substr(series.size() + 1), &value) ? value : -1;
    }
  }
  return -1;
}

absl::StatusOr<google::protobuf::Value> ParseJsonValue(const std::string& text) {
  google::protobuf::Value parsed;
  const auto status = google::protobuf::util::JsonStringToMessage(text, &parsed);
  if (!status.ok()) return absl::InvalidArgumentError(status.ToString());
  return parsed;
}

const google::protobuf::Value& JsonField(const google::protobuf::Value& object,
                                         const std::string& name) {
  static const google::protobuf::Value kNull;
  const auto& fields = object.struct_value().fields();
  const auto found = fields.find(name);
  return found == fields.end() ? kNull : found->second;
}

}  // namespace dcs::integration
