// Copyright 2026 The DCS Authors.
#include "services/cli/run_follower.h"

#include <atomic>
#include <csignal>
#include <iostream>

#include "run/evaluation_log.h"
#include "services/cli/run_client.h"
#include "services/cli/training_report.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

std::atomic<bool> detach_requested{false};
extern "C" void RequestDetach(int) { detach_requested = true; }

}  // namespace

int FollowRun(const std::string& address, const std::string& run_id, const std::string& out_dir,
              const GlobalFlags& flags) {
  detach_requested = false;
  std::signal(SIGINT, RequestDetach);
  std::signal(SIGTERM, RequestDetach);
  ProgressPrinter progress;
  absl::StatusOr<v1::Run> run = WatchRun(
      address, run_id, flags.timeout,
      [&progress](const v1::Run& changed) { progress.Update(ProgressLineOf(changed.progress())); },
      [] { return detach_requested.load(); });
  progress.Finish();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (absl::IsCancelled(run.status())) {
    std::cerr << "dcs: detached from " << run_id << " (it goes on); follow it with: dcs runs "
              << "watch " << run_id << std::endl;
    return kExitInterrupted;
  }
  if (!run.ok()) return FailCommand(run.status());
  if (run->state() != v1::RUN_STATE_COMPLETED) {
    std::cerr << "dcs: " << run_id << " " << RunStateName(run->state())
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
