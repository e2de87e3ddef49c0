// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_SCHEDULE_PREVIEW_H_
#define DCS_REPORT_SCHEDULE_PREVIEW_H_

// Schedule previews, as the paper's appendix figure shows them (`dcs schedule preview`): each
// schedule run over a few episodes whose initial values come from a pool, the episodes laid
// end to end, values normalised to [-1, 1] over the training range; one panel per family, one
// curve per setting of its key hyperparameters. Thread-safe (pure functions).

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "env/schedule_config.h"
#include "report/line_chart.h"

namespace dcs::report {

struct PreviewCurve {
  std::string label;  // e.g. "amplitude_frac 0.5, period 125"
  env::ScheduleConfig config;
};

struct PreviewPanel {
  std::string title;  // e.g. "sinusoidal"
  std::vector<PreviewCurve> curves;
};

// The panel of `family` with two or three settings of its key hyperparameters (amplitude,
// step size, drift rate, ...), in the builder's fraction form; "all": every family of the
// paper's figure (the eleven, without sequential). INVALID_ARGUMENT for an unknown family.
absl::StatusOr<std::vector<PreviewPanel>> FamilyPreviewPanels(absl::string_view family);

struct PreviewOptions {
  double lo = 0.35;  // the training range (default: the paper's CartPole pole length)
  double hi = 0.75;
  int pool_size = 3;  // episode-initial values: pool-N over [lo, hi], drawn at random
  int episodes = 3;
  int steps = 500;  // transitions per episode
  uint64_t seed = 0;
};

// One curve's values: episodes * steps of them, episode after episode.
struct PreviewTrajectory {
  int panel = 0;
  int curve = 0;
  std::vector<double> values;
};

// Runs every curve. INVALID_ARGUMENT for an invalid schedule config (naming the panel) or
// options (lo >= hi, episodes or steps < 1, pool_size < 1).
absl::StatusOr<std::vector<PreviewTrajectory>> RunPreview(const std::vector<PreviewPanel>& panels,
                                                          const PreviewOptions& options);

// Comma-separated values with a header: panel,curve,episode,t,step,value,normalized.
std::string PreviewCsv(const std::vector<PreviewPanel>& panels,
                       const std::vector<PreviewTrajectory>& trajectories,
                       const PreviewOptions& options);

// The figure, named `name` (its files' stem; report/line_chart.h): a panel per preview
// panel, a line per curve of normalised values against the step; dashed lines at episode
// boundaries, dotted at -1, 0 and +1, and room above +1 for the legend.
LineChart PreviewChart(const std::vector<PreviewPanel>& panels,
                       const std::vector<PreviewTrajectory>& trajectories,
                       const PreviewOptions& options, std::string name);

}  // namespace dcs::report

#endif  // DCS_REPORT_SCHEDULE_PREVIEW_H_
