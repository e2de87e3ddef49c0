// Copyright 2026 The DCS Authors.
#include "services/cli/command_output.h"
#include "services/cli/training_report.h"

#include <unistd.h>

#include <algorithm>
#include <iostream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "run/evaluation_log.h"

namespace dcs::services::cli {

ProgressPrinter::ProgressPrinter() : terminal_(isatty(STDERR_FILENO) == 1) {}

void ProgressPrinter::Update(const ProgressLine& p) {
  const bool new_evaluation =
      p.evaluation_step.has_value() && p.evaluation_step != last_evaluation_;
  last_evaluation_ = p.evaluation_step;
  if (!terminal_ && !new_evaluation) return;
  const int64_t shown = std::min(p.timesteps, p.total_timesteps);
  std::string line = absl::StrFormat(
      "step %d/%d (%d%%)  %.0f steps/s  return %.1f", p.timesteps, p.total_timesteps,
      shown * 100 / std::max<int64_t>(p.total_timesteps, 1), p.steps_per_second,
      p.recent_return);
  if (p.evaluation_step.has_value()) {
    absl::StrAppend(&line, absl::StrFormat("  eval@%d %.1f", *p.evaluation_step, p.avg_combined));
  }
  if (terminal_) {
    std::cerr << "\r\033[K" << line << std::flush;
  } else {
    std::cerr << line << std::endl;
  }
}

void ProgressPrinter::Finish() {
  if (terminal_) std::cerr << std::endl;
}

void PrintRunSummary(const RunSummary& summary, OutputFormat format) {
  const v1::EvaluationLog& log = summary.log;
  if (format == OutputFormat::kJson) {
    std::cout << CommandJson(log) << std::endl;
    return;
  }
  std::cout << "run           " << summary.dir << "\n"
            << "steps         " << summary.timesteps << " (" << summary.updates << " updates)\n"
            << "kernels       " << summary.kernels << "\n";
  if (summary.seconds.has_value()) {
    const run::PhaseSeconds& s = *summary.seconds;
    std::cout << absl::StrFormat(
        "time          %.2f s: rollouts %.2f, updates %.2f, evaluations %.2f, checkpoints %.2f\n",
        s.rollouts + s.updates + s.evaluations + s.checkpoints, s.rollouts, s.updates,
        s.evaluations, s.checkpoints);
  }
  if (log.evaluations_size() == 0) return;
  const v1::Evaluation& last = log.evaluations(log.evaluations_size() - 1);
  std::cout << absl::StrFormat(
      "last          avg_combined %.1f at step %d (id %.1f, ood_low %.1f, ood_high %.1f)\n",
      log.last(), last.step(), last.id().mean(), last.ood_low().mean(), last.ood_high().mean());
  if (log.best_anytime_index() >= 0) {
    std::cout << absl::StrFormat("best-anytime  avg_combined %.1f at step %d\n",
                                 log.best_anytime(),
                                 log.evaluations(log.best_anytime_index()).step());
  }
  std::cout << "evaluations   " << run::EvaluationCsvPath(summary.dir) << std::endl;
}

}  // namespace dcs::services::cli
