// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_TRAINING_REPORT_H_
#define DCS_SERVICES_CLI_TRAINING_REPORT_H_

// What `dcs train` shows of a run, in process or on a cluster (`--cluster`, `dcs runs
// watch`): a progress line after each update, and a summary of the finished run. Confined to
// main's thread.

#include <cstdint>
#include <optional>
#include <string>

#include "dcs/v1/evaluation.pb.h"
#include "run/phase_seconds.h"
#include "services/cli/cli_command.h"

namespace dcs::services::cli {

struct ProgressLine {
  int64_t timesteps = 0;
  int64_t total_timesteps = 0;
  double steps_per_second = 0;
  double recent_return = 0;  // NaN before the first episode
  // The latest evaluation, if any.
  std::optional<int64_t> evaluation_step;
  double avg_combined = 0;
};

// On a terminal, one line rewritten after every update; otherwise a line per evaluation.
class ProgressPrinter {
 public:
  ProgressPrinter();
  void Update(const ProgressLine& line);
  void Finish();

 private:
  const bool terminal_;
  std::optional<int64_t> last_evaluation_;
};

// The summary of a finished run: where it is, its steps and updates, the kernels it was
// trained with, where its time went when it ran in this process, its scores (table), or the
// evaluation log (JSON), on stdout.
struct RunSummary {
  std::string dir;
  int64_t timesteps = 0;
  int64_t updates = 0;
  std::string kernels;
  std::optional<run::PhaseSeconds> seconds;
  v1::EvaluationLog log;
};
void PrintRunSummary(const RunSummary& summary, OutputFormat format);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_TRAINING_REPORT_H_
