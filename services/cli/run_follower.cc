// Copyright 2026 The DCS Authors.
#include "services/cli/run_follower.h"

#include <iostream>

#include "run/evaluation_log.h"
#include "services/cli/command_output.h"
#include "services/cli/detach.h"
#include "services/cli/run_client.h"
#include "services/cli/training_report.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
int FollowRun(const std::string& address, const std::string& run_id, const std::string& out_dir,
              const GlobalFlags& flags) {
  ProgressPrinter progress;
  absl::StatusOr<v1::Run> run;
  {
    const DetachOnInterrupt detach;
    run = WatchRun(address, run_id,
                   {.on_update =
                        [&progress](const v1::Run& changed) {
                          progress.Update(ProgressLineOf(changed.progress()));
                        },
                    .interrupted = [&detach] { return detach.requested(); },
                    .on_lost =
                        [&progress](const absl::Status& status) {
                          progress.Finish();  // the progress line stays above the message
                          std::cerr << WatchLostMessage(status) << std::endl;
                        }});
  }
  progress.Finish();
  if (absl::IsCancelled(run.status())) {
    std::cerr << "dcs: detached from " << run_id << " (it goes on); follow it with: dcs runs "
              << "watch " << run_id << std::endl;
    return kExitInterrupted;
  }
  if (!run.ok()) return FailCommand(run.status());
  if (run->state() != v1::RUN_STATE_COMPLETED) {
    std::cerr << "dcs: " << run_id << " " << EnumWordOf(run->state())
              << (run->error().empty() ? "" : ": ") << run->error() << std::endl;
    return kExitFailure;
  }
  if (absl::Status status = DownloadRun(address, run_id, out_dir, flags.timeout); !status.ok()) {
    return FailCommand(status);
  }
  absl::StatusOr<v1::EvaluationLog> log = run::ReadEvaluationLog(out_dir);
  if (!log.ok()) return FailCommand(log.status());
  PrintRunSummary({.dir = out_dir,
                   .timesteps = run->progress().timesteps(),
                   .updates = run->progress().policy_version(),
                   .kernels = run->learner_numerics(),
                   .log = *std::move(log)},
                  flags.output);
  return kExitOk;
}

}  // namespace dcs::services::cli
