// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_RUN_DIRECTORY_H_
#define DCS_RUN_RUN_DIRECTORY_H_

// A run's directory, as `dcs train` lays it out:
//   config.yaml                  the run's config as it was started (`--seed` applied)
//   checkpoints/                 run/run_checkpoint.h
//   evaluations.csv, .json       run/evaluation_log.h
// A run starts in a directory that holds none, and resumes from one that holds its config.
// Thread-compatible (the file system is shared with other processes; nothing here locks it).

#include <cstdint>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "run/run_spec.h"

namespace dcs::run {

// A run as requested: its checked spec, its config as stored in its directory, the directory.
// Nothing on disk has changed yet.
struct RunRequest {
  RunSpec spec;
  std::string config_text;
  std::string dir;
};

// The config text with `seed` set (YAML comments are not kept); the text unchanged if it is
// not a YAML mapping, for ParseRunSpecYaml to report.
std::string ConfigWithSeed(const std::string& config_text, uint64_t seed);

// The run of `config_text` (read from `config_path`, named so in errors) in `dir`, or, if `dir`
// is empty, in <data_dir>/runs/<config file name without .yaml>-seed<seed>. INVALID_ARGUMENT as
// ParseRunSpecYaml.
absl::StatusOr<RunRequest> RequestRun(std::string config_text, const std::string& config_path,
                                      std::string dir, const std::string& data_dir);

// The run stored in `dir`, to resume. NOT_FOUND if `dir` holds none; INVALID_ARGUMENT if its
// config does not parse.
absl::StatusOr<RunRequest> StoredRun(std::string dir);

// OK if `request` may start: its directory holds no run. FAILED_PRECONDITION otherwise.
absl::Status CheckNewRun(const RunRequest& request);

// OK if `request` may resume: its directory holds a run of the same config text. NOT_FOUND if
// it holds none; FAILED_PRECONDITION naming the stored config and `config_name` if another.
absl::Status CheckResumedRun(const RunRequest& request, absl::string_view config_name);

// Creates `request.dir` with the run's config in it. PERMISSION_DENIED (naming the directory)
// if it cannot be made; as WriteFileAtomically for the config.
absl::Status CreateRunDirectory(const RunRequest& request);

}  // namespace dcs::run

#endif  // DCS_RUN_RUN_DIRECTORY_H_
