// Copyright 2026 The DCS Authors.
#include "coordinator/run_submission.h"

#include <utility>

#include "common/status_macros.h"
#include "env/env_registry.h"
#include "run/run_plan.h"

namespace dcs::coordinator {

absl::StatusOr<run::RunRequest> CheckSubmittedRun(std::string config_text,
                                                  const std::string& config_name,
                                                  std::optional<uint64_t> seed) {
  if (seed.has_value()) config_text = run::ConfigWithSeed(config_text, *seed);
  DCS_ASSIGN_OR_RETURN(run::RunRequest request,
                       run::RequestRun(std::move(config_text), config_name, /*dir=*/"-",
                                       /*data_dir=*/""));
  DCS_RETURN_IF_ERROR(CheckPlannable(request.spec));
  return request;
}

absl::Status CheckPlannable(const run::RunSpec& spec) {
  return env::VisitEnvironment(spec.env, [&]<typename Env>() {
    return run::PlanRun(spec, Env::Features()).status();
  });
}

RunSubmission SubmissionOf(const run::RunRequest& request, std::string request_id) {
  return {.request_id = std::move(request_id),
          .config = request.config_text,
          .seed = request.spec.seed,
          .env = request.spec.env,
          .n_envs = request.spec.n_envs,
          .total_timesteps = request.spec.total_timesteps};
}

}  // namespace dcs::coordinator
