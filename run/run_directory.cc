// Copyright 2026 The DCS Authors.
#include "run/run_directory.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <system_error>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "run/run_spec_yaml.h"

namespace dcs::run {
namespace {

namespace fs = std::filesystem;

constexpr char kConfigFile[] = "config.yaml";

std::string ConfigPath(const std::string& dir) { return (fs::path(dir) / kConfigFile).string(); }

}  // namespace

std::string ConfigWithSeed(const std::string& config_text, uint64_t seed) {
  try {
    YAML::Node root = YAML::Load(config_text);
    if (!root.IsMap()) return config_text;
    root["seed"] = seed;
    return absl::StrCat(YAML::Dump(root), "\n");
  } catch (const YAML::Exception&) {
    return config_text;
  }
}

absl::StatusOr<RunRequest> RequestRun(std::string config_text, const std::string& config_path,
                                      std::string dir, const std::string& data_dir) {
  DCS_ASSIGN_OR_RETURN(RunSpec spec, ParseRunSpecYaml(config_text, config_path));
  if (dir.empty()) {
    dir = (fs::path(data_dir) / "runs" /
           absl::StrCat(fs::path(config_path).stem().string(), "-seed", spec.seed))
              .string();
  }
  return RunRequest{
      .spec = std::move(spec), .config_text = std::move(config_text), .dir = std::move(dir)};
}

absl::StatusOr<RunRequest> StoredRun(std::string dir) {
  const std::string path = ConfigPath(dir);
  absl::StatusOr<std::string> text = ReadFile(path);
  if (!text.ok()) return absl::NotFoundError(absl::StrCat("no run to resume: ", path));
  DCS_ASSIGN_OR_RETURN(RunSpec spec, ParseRunSpecYaml(*text, path));
  return RunRequest{
      .spec = std::move(spec), .config_text = *std::move(text), .dir = std::move(dir)};
}

absl::Status CheckNewRun(const RunRequest& request) {
  if (fs::exists(ConfigPath(request.dir))) {
    return absl::FailedPreconditionError(absl::StrCat(request.dir, " already holds a run"));
  }
  return absl::OkStatus();
}

absl::Status CheckResumedRun(const RunRequest& request, absl::string_view config_name) {
  const std::string path = ConfigPath(request.dir);
  absl::StatusOr<std::string> stored = ReadFile(path);
  if (!stored.ok()) return absl::NotFoundError(absl::StrCat("no run to resume in ", request.dir));
  if (*stored != request.config_text) {
    return absl::FailedPreconditionError(absl::StrCat(
        request.dir, " holds a run of another config (", path, " differs from ", config_name, ")"));
  }
  return absl::OkStatus();
}

absl::Status CreateRunDirectory(const RunRequest& request) {
  std::error_code error;
  fs::create_directories(request.dir, error);
  if (error) {
    return absl::PermissionDeniedError(
        absl::StrCat("cannot create ", request.dir, ": ", error.message()));
  }
  return WriteFileAtomically(ConfigPath(request.dir), request.config_text);
}

}  // namespace dcs::run
