// Copyright 2026 The DCS Authors.
#include "report/schedule_preview.h"

#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/random.h"
#include "common/round_trip.h"
#include "common/status_macros.h"
#include "env/context_pool.h"
#include "env/schedule.h"

namespace dcs::report {
namespace {

using Params = std::map<std::string, env::ScheduleParam>;

PreviewCurve Curve(std::string label, std::string family, Params params) {
  return {std::move(label), {.family = std::move(family), .params = std::move(params)}};
}

// The figure's curves: the paper's presets where it has them (docs/reference.md, "Presets"), else
// the builder's defaults next to one contrasting setting.
std::vector<PreviewPanel> AllFamilyPanels() {
  using V = std::vector<double>;
  return {
      {"identity (static)", {Curve("constant", "identity", {})}},
      {"sinusoidal",
       {Curve("amplitude_frac 0.5, period 125", "sinusoidal",
              {{"amplitude_frac", 0.5}, {"period", 125.0}}),
        Curve("amplitude_frac 1.0, period 250", "sinusoidal",
              {{"amplitude_frac", 1.0}, {"period", 250.0}})}},
      {"cosine_annealing",
       {Curve("T_0 250, radius_frac 0.2", "cosine_annealing",
              {{"T_0", 250.0}, {"neighborhood_radius_frac", 0.2}, {"direction", "random"}}),
        Curve("T_0 125, full range", "cosine_annealing",
              {{"T_0", 125.0}, {"direction", "random"}})}},
      {"continuous_incrementer",
       {Curve("delta_frac 0.005", "continuous_incrementer", {{"delta_frac", 0.005}}),
        Curve("delta_frac 0.002", "continuous_incrementer", {{"delta_frac", 0.002}})}},
      {"piecewise_constant",
       {Curve("interval 30-50", "piecewise_constant",
              {{"values", V{0.35, 0.45, 0.55, 0.65, 0.75}}, {"interval_range", V{30, 50}}}),
        Curve("interval 100-150", "piecewise_constant",
              {{"values", V{0.35, 0.45, 0.55, 0.65, 0.75}}, {"interval_range", V{100, 150}}})}},
      {"random_walk",
       {Curve("std_frac 0.01", "random_walk", {{"std_frac", 0.01}}),
        Curve("std_frac 0.03", "random_walk", {{"std_frac", 0.03}})}},
      {"sudden_jump",
       {Curve("step 0.1-0.3, interval 10-30", "sudden_jump", {}),
        Curve("step 0.2-0.4, interval 60-120", "sudden_jump",
              {{"step_size_frac_range", V{0.2, 0.4}}, {"interval_range", V{60, 120}}})}},
      {"ornstein_uhlenbeck",
       {Curve("theta 0.05, sigma_frac 0.08", "ornstein_uhlenbeck", {}),
        Curve("theta 0.01, sigma_frac 0.03", "ornstein_uhlenbeck",
              {{"theta", 0.01}, {"sigma_frac", 0.03}})}},
      {"sinusoidal_jump",
       {Curve("amplitude_frac 0.3", "sinusoidal_jump", {}),
        Curve("amplitude_frac 0.15", "sinusoidal_jump", {{"amplitude_frac", 0.15}})}},
      {"phased_ou",
       {Curve("sigma_frac 0.04", "phased_ou", {}),
        Curve("sigma_frac 0.015", "phased_ou", {{"sigma_frac", 0.015}})}},
      {"levy_walk",
       {Curve("std_frac 0.008", "levy_walk", {}),
        Curve("std_frac 0.02", "levy_walk", {{"std_frac", 0.02}})}},
  };
}

double Normalized(double value, const PreviewOptions& options) {
  return 2 * (value - options.lo) / (options.hi - options.lo) - 1;
}

}  // namespace

absl::StatusOr<std::vector<PreviewPanel>> FamilyPreviewPanels(absl::string_view family) {
  std::vector<PreviewPanel> all = AllFamilyPanels();
  if (family == "all") return all;
  for (PreviewPanel& panel : all) {
    if (panel.curves.front().config.family == family) return std::vector<PreviewPanel>{panel};
  }
  std::vector<std::string> names = {"all"};
  for (const PreviewPanel& panel : all) names.push_back(panel.curves.front().config.family);
  return absl::InvalidArgumentError(absl::StrCat("no preview of schedule family '", family,
                                                 "' (known: ", absl::StrJoin(names, ", "), ")"));
}

absl::StatusOr<std::vector<PreviewTrajectory>> RunPreview(const std::vector<PreviewPanel>& panels,
                                                          const PreviewOptions& options) {
  if (options.episodes < 1 || options.steps < 1) {
    return absl::InvalidArgumentError("a preview needs at least one episode of one step");
  }
  DCS_ASSIGN_OR_RETURN(const env::ContextPool pool,
                       env::ContextPool::OfSize(options.lo, options.hi, options.pool_size));
  std::vector<PreviewTrajectory> trajectories;
  for (size_t p = 0; p < panels.size(); ++p) {
    for (size_t c = 0; c < panels[p].curves.size(); ++c) {
      const uint32_t seed =
          StreamSeed(options.seed, "preview_schedule", {p, c}).GenerateState32(1)[0];
      absl::StatusOr<env::ScheduleSpec> spec =
          env::ParseScheduleSpec(panels[p].curves[c].config, options.lo, options.hi, seed);
      if (!spec.ok()) {
        return absl::InvalidArgumentError(
            absl::StrCat("panel '", panels[p].title, "': ", spec.status().message()));
      }
      std::unique_ptr<env::Schedule> schedule = env::MakeSchedule(*spec);
      PreviewTrajectory trajectory{.panel = static_cast<int>(p), .curve = static_cast<int>(c)};
      for (int episode = 0; episode < options.episodes; ++episode) {
        const auto e = static_cast<uint64_t>(episode);
        Random pool_random(StreamSeed(options.seed, "pool", {0, e}));
        const double initial = pool.Select(env::ContextPool::Selection::kRandom, e, 0,
                                           pool_random);
        const std::vector<double> values = env::ScheduleTrajectory(
            *schedule, initial, {.episode = e, .slot = 0}, options.steps);
        trajectory.values.insert(trajectory.values.end(), values.begin(), values.end());
      }
      trajectories.push_back(std::move(trajectory));
    }
  }
  return trajectories;
}

std::string PreviewCsv(const std::vector<PreviewPanel>& panels,
                       const std::vector<PreviewTrajectory>& trajectories,
                       const PreviewOptions& options) {
  std::string csv = "panel,curve,episode,t,step,value,normalized\n";
  for (const PreviewTrajectory& trajectory : trajectories) {
    const PreviewPanel& panel = panels[trajectory.panel];
    for (size_t i = 0; i < trajectory.values.size(); ++i) {
      const double value = trajectory.values[i];
      absl::StrAppend(&csv, "\"", panel.title, "\",\"", panel.curves[trajectory.curve].label,
                      "\",", i / options.steps, ",", i % options.steps, ",", i, ",",
                      RoundTrip(value), ",", RoundTrip(Normalized(value, options)), "\n");
    }
  }
  return csv;
}

LineChart PreviewChart(const std::vector<PreviewPanel>& panels,
                       const std::vector<PreviewTrajectory>& trajectories,
                       const PreviewOptions& options, std::string name) {
  LineChart chart{.name = std::move(name),
                  .title = absl::StrCat("Schedule families: ", options.episodes,
                                        " episodes of ", options.steps,
                                        " steps, normalised to [-1, 1] over [", options.lo, ", ",
                                        options.hi, "]"),
                  .columns = 3,
                  .panel_width = 420,
                  .panel_height = 300};
  const double steps = static_cast<double>(options.episodes) * options.steps;
  for (const PreviewPanel& preview : panels) {
    LinePanel panel{.title = preview.title,
                    .x_label = "step",
                    .y_label = "normalised context",
                    .x_range = std::make_pair(0.0, steps),
                    .y_range = std::make_pair(-1.2, 2.1),
                    .y_markers = {-1, 0, 1},
                    .y_tics = {{-1}, {-0.5}, {0}, {0.5}, {1}},
                    .legend = LegendPlace::kTopLeft};
    for (int e = 1; e < options.episodes; ++e) {
      panel.x_markers.push_back(static_cast<double>(e) * options.steps);
    }
    chart.panels.push_back(std::move(panel));
  }
  for (const PreviewTrajectory& trajectory : trajectories) {
    ChartLine line{.label = panels[trajectory.panel].curves[trajectory.curve].label};
    for (size_t i = 0; i < trajectory.values.size(); ++i) {
      line.x.push_back(static_cast<double>(i));
      line.y.push_back(Normalized(trajectory.values[i], options));
    }
    chart.panels[trajectory.panel].lines.push_back(std::move(line));
  }
  return chart;
}

}  // namespace dcs::report
