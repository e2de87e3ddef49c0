// Copyright 2026 The DCS Authors.
#include "services/cli/sweep_view.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/time/time.h"
#include "common/text_table.h"
#include "coordinator/iqm.h"
#include "services/cli/command_output.h"
#include "services/cli/run_client.h"

namespace dcs::services::cli {
namespace {

// A trial's runs, counted.
struct TrialCount {
  int completed = 0;
  int running = 0;
  int queued = 0;
  int failed = 0;
  std::vector<double> last;  // the completed runs' last avg_combined
};

std::vector<TrialCount> CountTrials(const v1::GetSweepResponse& response) {
  std::vector<TrialCount> trials(response.sweep().trials_size());
  for (const v1::Run& run : response.runs()) {
    if (!run.has_trial() || run.trial() < 0 || run.trial() >= static_cast<int>(trials.size())) {
      continue;
    }
    TrialCount& trial = trials[run.trial()];
    switch (run.state()) {
      case v1::RUN_STATE_COMPLETED:
        ++trial.completed;
        if (run.progress().has_avg_combined()) trial.last.push_back(run.progress().avg_combined());
        break;
      case v1::RUN_STATE_RUNNING: ++trial.running; break;
      case v1::RUN_STATE_QUEUED: ++trial.queued; break;
      case v1::RUN_STATE_FAILED: ++trial.failed; break;
      default: break;
    }
  }
  return trials;
}

// The IQM of the completed runs' last scores; nullopt before any completed. An error (a score
// that is NaN) is shown, not taken for "none yet".
std::optional<absl::StatusOr<double>> Iqm(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  return coordinator::InterquartileMean(values);
}

std::string TrialName(const v1::Trial& trial) {
  return absl::StrCat(trial.condition(), " (", trial.observe(), ")");
}

}  // namespace

std::string SweepHeadline(const v1::GetSweepResponse& response) {
  const v1::Sweep& sweep = response.sweep();
  std::string line = absl::StrCat(sweep.sweep_id(), " ", sweep.name(), ": ",
                                   EnumWordOf(sweep.state()), ", ", sweep.completed(), "/",
                                   sweep.runs(), " runs done (", sweep.running(), " running, ",
                                   sweep.queued(), " queued, ", sweep.failed(), " failed)");
  double steps_per_second = 0;
  double steps_left = 0;
  for (const v1::Run& run : response.runs()) {
    const v1::RunProgress& progress = run.progress();
    if (run.state() == v1::RUN_STATE_RUNNING) {
      steps_per_second += progress.steps_per_second();
      steps_left += std::max<double>(0, progress.total_timesteps() - progress.timesteps());
    } else if (run.state() == v1::RUN_STATE_QUEUED) {
      steps_left += std::max<double>(0, progress.total_timesteps() - progress.timesteps());
    }
  }
  if (steps_per_second > 0) {
    absl::StrAppend(&line, absl::StrFormat(", %.0f steps/s, ETA %s", steps_per_second,
                                           absl::FormatDuration(absl::Seconds(
                                               std::round(steps_left / steps_per_second)))));
  }
  std::vector<std::vector<double>> last_by_trial;
  for (TrialCount& trial : CountTrials(response)) last_by_trial.push_back(std::move(trial.last));
  if (const std::optional<coordinator::HighestIqmGroup> best =
          coordinator::HighestIqm(last_by_trial)) {
    absl::StrAppend(&line, absl::StrFormat(", best: %s %.1f",
                                           TrialName(sweep.trials(static_cast<int>(best->index))),
                                           best->iqm));
  }
  return line;
}

std::string SweepProgressView(const v1::GetSweepResponse& response) {
  const v1::Sweep& sweep = response.sweep();
  const std::vector<TrialCount> trials = CountTrials(response);
  std::vector<std::vector<std::string>> rows = {
      {"CONDITION", "MODE", "DONE", "RUNNING", "QUEUED", "FAILED", "LAST (IQM)"}};
  for (size_t t = 0; t < trials.size(); ++t) {
    const TrialCount& count = trials[t];
    const std::optional<absl::StatusOr<double>> iqm = Iqm(count.last);
    rows.push_back({sweep.trials(t).condition(), sweep.trials(t).observe(),
                    absl::StrCat(count.completed, "/", sweep.seeds()),
                    absl::StrCat(count.running), absl::StrCat(count.queued),
                    absl::StrCat(count.failed),
                    !iqm.has_value() ? "-"
                    : iqm->ok()      ? absl::StrFormat("%.1f", **iqm)
                                     : absl::StrCat("error: ", iqm->status().message())});
  }
  return absl::StrCat(SweepHeadline(response), "\n", RenderTable(rows));
}

}  // namespace dcs::services::cli
