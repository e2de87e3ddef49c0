// Copyright 2026 The DCS Authors.
#include "services/cli/figure_render.h"

#include <sys/wait.h>

#include <filesystem>
#include <optional>
#include <system_error>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "services/cli/child_process.h"

namespace dcs::services::cli {
namespace {

namespace fs = std::filesystem;

constexpr size_t kMaxQuotedOutput = 4000;  // bytes of gnuplot's output an error quotes

absl::Status CheckFileName(const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos) {
    return absl::InvalidArgumentError(
        absl::StrCat("figure file name '", name, "' is not a plain file name"));
  }
  return absl::OkStatus();
}

std::string Quote(absl::string_view output) {
  output = absl::StripAsciiWhitespace(output);
  if (output.empty()) return "(no output)";
  if (output.size() <= kMaxQuotedOutput) return std::string(output);
  return absl::StrCat("...", output.substr(output.size() - kMaxQuotedOutput));
}

}  // namespace

absl::Status WriteFigureFiles(const report::GnuplotFigure& figure, const std::string& dir) {
  DCS_RETURN_IF_ERROR(report::CheckFigureName(figure.name));
  for (const report::DataFile& data : figure.data) {
    DCS_RETURN_IF_ERROR(CheckFileName(data.name));
  }
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) {
    return absl::PermissionDeniedError(
        absl::StrCat("cannot create the figure directory ", dir, ": ", error.message()));
  }
  for (const report::DataFile& data : figure.data) {
    DCS_RETURN_IF_ERROR(WriteFileAtomically((fs::path(dir) / data.name).string(), data.csv));
  }
  return WriteFileAtomically((fs::path(dir) / figure.ScriptFileName()).string(), figure.script);
}

absl::StatusOr<RenderedFigure> RenderFigure(const report::GnuplotFigure& figure,
                                            report::FigureFormat format, const std::string& dir,
                                            const RenderOptions& options) {
  DCS_RETURN_IF_ERROR(WriteFigureFiles(figure, dir));
  const std::string script = (fs::path(dir) / figure.ScriptFileName()).string();
  const std::optional<std::string> gnuplot = FindProgram(options.gnuplot);
  if (!gnuplot.has_value()) {
    return absl::FailedPreconditionError(absl::StrCat(
        "cannot render ", script, ": gnuplot ('", options.gnuplot,
        "') is not installed or not on PATH; install it (Debian: apt-get install gnuplot-nox) "
        "and run `gnuplot ", figure.ScriptFileName(), "` in ", dir));
  }
  const std::string image = (fs::path(dir) / figure.ImageFileName(format)).string();
  const std::string output_path =
      (fs::path(dir) / absl::StrCat(".", figure.name, ".gnuplot-output")).string();
  std::error_code ignored;
  fs::remove(image, ignored);
  fs::remove(output_path, ignored);
  const absl::string_view format_name = NameOf(report::kFigureFormatNames, format);
  absl::StatusOr<ChildProcess> child = ChildProcess::Start(
      {.path = *gnuplot,
       .args = {"-e", absl::StrCat("format='", format_name, "'"), figure.ScriptFileName()},
       .output_path = output_path,
       .working_directory = dir});
  if (!child.ok()) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot render ", script, ": ", child.status().message()));
  }
  const std::optional<int> status = child->Wait(options.timeout);
  if (!status.has_value()) child->Stop(absl::ZeroDuration());
  const std::string output = ReadFile(output_path).value_or("");
  fs::remove(output_path, ignored);
  if (!status.has_value()) {
    return absl::DeadlineExceededError(absl::StrCat("gnuplot took more than ",
                                                    absl::FormatDuration(options.timeout),
                                                    " on ", script, "; killed it"));
  }
  if (!WIFEXITED(*status) || WEXITSTATUS(*status) != 0) {
    return absl::InternalError(absl::StrCat("gnuplot failed on ", script, " (",
                                            DescribeExit(*status), "): ", Quote(output)));
  }
  if (!fs::is_regular_file(image, ignored) || fs::file_size(image, ignored) == 0) {
    return absl::InternalError(absl::StrCat("gnuplot wrote no ", image, " from ", script, ": ",
                                            Quote(output)));
  }
  return RenderedFigure{.path = image, .gnuplot_output = output};
}

}  // namespace dcs::services::cli
