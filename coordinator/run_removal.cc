// Copyright 2026 The DCS Authors.
#include "coordinator/run_removal.h"

#include <filesystem>
#include <system_error>
#include <utility>

#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "coordinator/run_files.h"

namespace dcs::coordinator {
namespace {

namespace fs = std::filesystem;

// Removes run `run_id`'s directory in `data_dir`, if it exists.
absl::Status RemoveRunDirectory(absl::string_view data_dir, absl::string_view run_id) {
  const std::string dir = RunDirectory(data_dir, run_id);
  std::error_code error;
  fs::remove_all(dir, error);
  return error ? FileError(error.value(), "cannot remove", dir) : absl::OkStatus();
}

}  // namespace

absl::StatusOr<RunRemoval> RemoveRuns(Store& store, absl::string_view data_dir,
                                      absl::Span<const std::string> run_ids) {
  RunRemoval removal;
  DCS_ASSIGN_OR_RETURN(removal.runs, store.runs().DeleteRuns(run_ids));
  for (const RunRecord& run : removal.runs) {
    removal.files.Update(RemoveRunDirectory(data_dir, run.id));
  }
  return removal;
}

absl::StatusOr<SweepRemoval> RemoveSweeps(Store& store, absl::string_view data_dir,
                                          absl::Span<const std::string> sweep_ids) {
  SweepRemoval removal;
  DCS_ASSIGN_OR_RETURN(removal.sweeps, store.sweeps().DeleteSweeps(sweep_ids));
  for (const RemovedSweep& sweep : removal.sweeps) {
    for (const RunRecord& run : sweep.runs) {
      removal.files.Update(RemoveRunDirectory(data_dir, run.id));
    }
  }
  return removal;
}

absl::StatusOr<std::vector<std::string>> RemoveLeftoverRunDirectories(Store& store,
                                                                      absl::string_view data_dir) {
  const fs::path runs = fs::path(std::string(data_dir)) / "runs";
  std::vector<std::string> names;
  std::error_code error;
  for (fs::directory_iterator entry(runs, error), end; !error && entry != end;
       entry.increment(error)) {
    if (entry->is_directory()) names.push_back(entry->path().filename().string());
  }
  if (error && error != std::errc::no_such_file_or_directory) {
    return FileError(error.value(), "cannot list", runs.string());
  }
  DCS_ASSIGN_OR_RETURN(std::vector<std::string> removed, store.runs().RemovedRuns(names));
  for (const std::string& run_id : removed) {
    DCS_RETURN_IF_ERROR(RemoveRunDirectory(data_dir, run_id));
  }
  return removed;
}

}  // namespace dcs::coordinator
