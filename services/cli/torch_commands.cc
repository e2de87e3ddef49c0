// Copyright 2026 The DCS Authors.
#include "services/cli/torch_commands.h"

#include <atomic>
#include <csignal>
#include <iostream>
#include <optional>
#include <string>

#include "absl/strings/string_view.h"
#include "common/status_macros.h"
#include "env/env_registry.h"
#include "learner/torch_runtime.h"
#include "learner/training_run.h"
#include "services/cli/training_report.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

// Set by SIGINT and SIGTERM: the run stops after its current update, with a checkpoint.
std::atomic<bool> stop_requested{false};
extern "C" void RequestStop(int) { stop_requested = true; }

}  // namespace

int TrainInProcess(const run::RunRequest& request, bool resume, int keep,
                   const GlobalFlags& global) {
  learner::PinNumericKernels(
      [](absl::string_view note) { std::cerr << "dcs: " << note << std::endl; });
  if (!resume) {
    if (absl::Status status = run::CreateRunDirectory(request); !status.ok()) {
      return FailCommand(status);
    }
  }
  if (absl::Status status = learner::PinTorchThreads(1); !status.ok()) {
    return FailCommand(status);
  }
  const run::RunSpec& spec = request.spec;
  const std::string& out_dir = request.dir;
  std::signal(SIGINT, RequestStop);
  std::signal(SIGTERM, RequestStop);
  ProgressPrinter progress;
  const learner::TrainingOptions options{
      .out_dir = out_dir,
      .resume = resume,
      .keep_checkpoints = keep,
      .on_update =
          [&progress](const learner::TrainingProgress& p) {
            ProgressLine line{.timesteps = p.timesteps,
                              .total_timesteps = p.total_timesteps,
                              .steps_per_second = p.steps_per_second,
                              .recent_return = p.recent_return};
            if (p.evaluation != nullptr) {
              line.evaluation_step = p.evaluation->step;
              line.avg_combined = p.evaluation->avg_combined;
            }
            progress.Update(line);
            return !stop_requested;
          }};
  std::optional<learner::TrainingResult> result;
  const absl::Status status =
      env::VisitEnvironment(spec.env, [&]<typename Env>() -> absl::Status {
        DCS_ASSIGN_OR_RETURN(result, learner::Train<Env>(spec, options));
        return absl::OkStatus();
      });
  progress.Finish();
  if (!status.ok()) return FailCommand(status);
  if (!result->complete) {
    std::cerr << "dcs: stopped at step " << result->state.timesteps
              << "; continue with: dcs train --resume --out " << out_dir << std::endl;
    return kExitInterrupted;
  }
  PrintRunSummary({.dir = out_dir,
                   .timesteps = result->state.timesteps,
                   .updates = result->state.rollouts,
                   .kernels = learner::NumericFingerprint(),
                   .seconds = result->seconds,
                   .log = result->log},
                  global.output);
  return kExitOk;
}

}  // namespace dcs::services::cli
