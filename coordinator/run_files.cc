// Copyright 2026 The DCS Authors.
#include "coordinator/run_files.h"

#include <algorithm>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "run/evaluation_log.h"

namespace dcs::coordinator {
namespace {

namespace fs = std::filesystem;

}  // namespace

std::string RunDirectory(absl::string_view data_dir, absl::string_view run_id) {
  return (fs::path(std::string(data_dir)) / "runs" / std::string(run_id)).string();
}

absl::StatusOr<CheckpointRecord> StoreCheckpoint(const std::string& run_dir,
                                                 const run::PackedCheckpoint& checkpoint,
                                                 const v1::EvaluationLog& log, int keep) {
  DCS_ASSIGN_OR_RETURN(const run::Checkpoint unpacked, run::UnpackCheckpoint(checkpoint));
  DCS_RETURN_IF_ERROR(run::WriteCheckpoint(run_dir, unpacked.state, unpacked.learner, keep));
  DCS_RETURN_IF_ERROR(run::WriteEvaluationLog(run_dir, log));
  return CheckpointRecord{.name = unpacked.name,
                          .timesteps = unpacked.state.timesteps,
                          .sha256 = checkpoint.learner_sha256};
}

absl::StatusOr<run::PackedCheckpoint> LatestCheckpoint(const std::string& run_dir) {
  DCS_ASSIGN_OR_RETURN(const run::Checkpoint checkpoint, run::ReadLatestCheckpoint(run_dir));
  return run::PackCheckpoint(checkpoint);
}

absl::StatusOr<std::vector<RunFile>> ReadRunFiles(const std::string& run_dir) {
  std::error_code error;
  if (!fs::is_directory(run_dir, error)) {
    return absl::NotFoundError(absl::StrCat("no run directory ", run_dir));
  }
  std::vector<RunFile> files;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(run_dir, error)) {
    if (!entry.is_regular_file()) continue;
    DCS_ASSIGN_OR_RETURN(std::string contents, ReadFile(entry.path()));
    files.push_back({.path = fs::relative(entry.path(), run_dir).string(),
                     .contents = std::move(contents)});
  }
  std::sort(files.begin(), files.end(),
            [](const RunFile& a, const RunFile& b) { return a.path < b.path; });
  return files;
}

}  // namespace dcs::coordinator
