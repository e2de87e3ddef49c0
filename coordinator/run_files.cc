// Copyright 2026 The DCS Authors.
#include "coordinator/run_files.h"

#include <sys/statvfs.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>

#include "absl/status/status.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "run/appended_evaluation_log.h"
#include "run/evaluation_log.h"

namespace dcs::coordinator {
namespace {

namespace fs = std::filesystem;

// A write that failed for a full disk (RESOURCE_EXHAUSTED) as one its caller may retry.
absl::Status RetryableWhenFull(absl::Status status) {
  if (!absl::IsResourceExhausted(status)) return status;
  return absl::UnavailableError(status.message());
}

}  // namespace

std::string RunDirectory(absl::string_view data_dir, absl::string_view run_id) {
  return (fs::path(std::string(data_dir)) / "runs" / std::string(run_id)).string();
}

absl::StatusOr<CheckpointRecord> StoreCheckpoint(const std::string& run_dir,
                                                 const run::PackedCheckpoint& checkpoint,
                                                 int64_t first_evaluation,
                                                 const v1::EvaluationLog& log_since, int keep) {
  // Stored as it came, checked against its SHA-256s but not decoded: the learner made it with
  // the same run library, and decoding and encoding it again cost a fifth of the coordinator's
  // time. Its learner reads it back whole, falling back to an older one if it cannot.
  DCS_ASSIGN_OR_RETURN(const int64_t timesteps, run::CheckPackedCheckpoint(checkpoint));
  DCS_RETURN_IF_ERROR(
      RetryableWhenFull(run::AppendEvaluationLog(run_dir, first_evaluation, log_since)));
  DCS_RETURN_IF_ERROR(RetryableWhenFull(run::WritePackedCheckpoint(run_dir, checkpoint, keep)));
  return CheckpointRecord{
      .name = checkpoint.name, .timesteps = timesteps, .sha256 = checkpoint.learner_sha256};
}

std::optional<EvaluationScores> ScoreEvaluations(const v1::EvaluationLog& log) {
  if (log.evaluations().empty()) return std::nullopt;
  const v1::Evaluation* latest = &log.evaluations(0);
  const v1::Evaluation* best = nullptr;
  for (const v1::Evaluation& evaluation : log.evaluations()) {
    if (evaluation.step() > latest->step()) latest = &evaluation;
    // NaN is never the best: every comparison with it is false.
    if (best == nullptr ? !std::isnan(evaluation.avg_combined())
                        : evaluation.avg_combined() > best->avg_combined()) {
      best = &evaluation;
    }
  }
  return EvaluationScores{
      .latest_step = latest->step(),
      .latest_avg_combined = latest->avg_combined(),
      .latest_id_return = latest->id().mean(),
      .latest_ood_low_return = latest->ood_low().mean(),
      .latest_ood_high_return = latest->ood_high().mean(),
      .best_step = best == nullptr ? latest->step() : best->step(),
      .best_avg_combined = best == nullptr ? std::nan("") : best->avg_combined()};
}

absl::StatusOr<DiskSpace> DiskSpaceOf(const std::string& data_dir) {
  struct statvfs space;
  if (::statvfs(data_dir.c_str(), &space) != 0) {
    return FileError(errno, "cannot measure the free space of", data_dir);
  }
  return DiskSpace{.free_bytes = static_cast<int64_t>(space.f_bavail * space.f_frsize),
                   .capacity_bytes = static_cast<int64_t>(space.f_blocks * space.f_frsize)};
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
  const bool appended = run::HasAppendedEvaluationLog(run_dir);
  std::vector<RunFile> files;
  if (appended) {
    DCS_ASSIGN_OR_RETURN(const v1::EvaluationLog log, run::ReadEvaluationLog(run_dir));
    for (run::EvaluationLogFile& file : run::EvaluationLogFiles(log)) {
      files.push_back({.path = std::move(file.name), .contents = std::move(file.contents)});
    }
  }
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(run_dir, error)) {
    if (!entry.is_regular_file()) continue;
    std::string path = fs::relative(entry.path(), run_dir).string();
    // The appended log's own files, and any left from before it (given above).
    if (appended && absl::StartsWith(path, "evaluations.")) continue;
    DCS_ASSIGN_OR_RETURN(std::string contents, ReadFile(entry.path()));
    files.push_back({.path = std::move(path), .contents = std::move(contents)});
  }
  std::sort(files.begin(), files.end(),
            [](const RunFile& a, const RunFile& b) { return a.path < b.path; });
  return files;
}

}  // namespace dcs::coordinator
