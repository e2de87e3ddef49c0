// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_RUN_SUBMISSION_H_
#define DCS_COORDINATOR_RUN_SUBMISSION_H_

// A run config submitted remotely, checked as `dcs train` checks one before it starts: parsed
// (run/run_spec_yaml.h: errors name the field, its path and line) and planned for its
// environment (run/run_plan.h), so nothing is queued that no learner could train.
// Thread-safe (pure functions).

#include <cstdint>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "coordinator/run_table.h"
#include "run/run_directory.h"

namespace dcs::coordinator {

// The run of `config_text` (named `config_name` in errors), with `seed` applied if given, to be
// stored in `dir`. INVALID_ARGUMENT as ParseRunSpecYaml and PlanRun, or for an unknown
// environment.
absl::StatusOr<run::RunRequest> CheckSubmittedRun(std::string config_text,
                                                  const std::string& config_name,
                                                  std::optional<uint64_t> seed);

// The store's submission of the checked run `request`, named `request_id`.
RunSubmission SubmissionOf(const run::RunRequest& request, std::string request_id);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_RUN_SUBMISSION_H_
