// Copyright 2026 The DCS Authors.
#include "services/cli/schedule_commands.h"

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "report/gnuplot_figure.h"
#include "report/line_chart.h"
#include "report/schedule_preview.h"
#include "run/schedule_yaml.h"
#include "services/cli/figure_render.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

struct PreviewFlags {
  std::string spec;  // a YAML file, a family name, or "all"
  std::string range = "0.35,0.75";
  report::PreviewOptions options;
  std::string out;
  std::string svg;
};

absl::StatusOr<std::vector<report::PreviewPanel>> PreviewPanels(const std::string& spec) {
  if (!std::filesystem::exists(spec)) return report::FamilyPreviewPanels(spec);
  DCS_ASSIGN_OR_RETURN(const std::string text, ReadFile(spec));
  DCS_ASSIGN_OR_RETURN(const std::vector<env::ScheduleConfig> configs,
                       run::ParseScheduleConfigsYaml(text, spec));
  std::vector<report::PreviewPanel> panels;
  for (size_t i = 0; i < configs.size(); ++i) {
    const std::string& family = configs[i].family;
    panels.push_back(
        {.title = configs.size() > 1 ? absl::StrCat(family, " #", i + 1) : family,
         .curves = {{.label = family, .config = configs[i]}}});
  }
  return panels;
}

// The figure of `--svg FILE`: named after FILE's stem, its files beside FILE.
absl::StatusOr<report::GnuplotFigure> PreviewFigure(
    const std::vector<report::PreviewPanel>& panels,
    const std::vector<report::PreviewTrajectory>& trajectories, const PreviewFlags& flags) {
  const std::filesystem::path svg(flags.svg);
  absl::StatusOr<report::GnuplotFigure> figure = report::LineChartFigure(
      report::PreviewChart(panels, trajectories, flags.options, svg.stem().string()));
  if (!figure.ok()) {
    return absl::InvalidArgumentError(absl::StrCat("--svg ", flags.svg, ": ",
                                                   figure.status().message()));
  }
  for (const report::DataFile& data : figure->data) {
    const std::filesystem::path path = svg.parent_path() / data.name;
    std::error_code data_error, out_error;
    const std::filesystem::path data_path = std::filesystem::weakly_canonical(path, data_error);
    const std::filesystem::path out_path = std::filesystem::weakly_canonical(flags.out, out_error);
    if (!data_error && !out_error && data_path == out_path) {
      return absl::InvalidArgumentError(absl::StrCat(
          "--svg ", flags.svg, " keeps the figure's data in ", path.string(),
          ", which is the --out file; give the figure another name"));
    }
  }
  return figure;
}

// Renders the figure with gnuplot beside `flags.svg` and moves the image to it.
absl::Status RenderPreviewFigure(const report::GnuplotFigure& figure, const PreviewFlags& flags) {
  const std::filesystem::path svg(flags.svg);
  const std::string dir = svg.has_parent_path() ? svg.parent_path().string() : ".";
  DCS_ASSIGN_OR_RETURN(const RenderedFigure rendered,
                       RenderFigure(figure, report::FigureFormat::kSvg, dir));
  if (std::filesystem::path(rendered.path).lexically_normal() != svg.lexically_normal()) {
    std::error_code error;
    std::filesystem::rename(rendered.path, svg, error);
    if (error) {
      return absl::PermissionDeniedError(absl::StrCat("cannot move ", rendered.path, " to ",
                                                      flags.svg, ": ", error.message()));
    }
  }
  std::cerr << "wrote the figure to " << flags.svg << " (gnuplot script "
            << (svg.parent_path() / figure.ScriptFileName()).string() << ", data "
            << (svg.parent_path() / figure.data.front().name).string() << ")" << std::endl;
  return absl::OkStatus();
}

absl::Status Preview(PreviewFlags flags) {
  DCS_ASSIGN_OR_RETURN(const std::vector<double> range, ParseNumberList(flags.range, "--range"));
  if (range.size() != 2) {
    return absl::InvalidArgumentError("--range: expected lo,hi (the training range)");
  }
  flags.options.lo = range[0];
  flags.options.hi = range[1];
  DCS_ASSIGN_OR_RETURN(const std::vector<report::PreviewPanel> panels, PreviewPanels(flags.spec));
  DCS_ASSIGN_OR_RETURN(const std::vector<report::PreviewTrajectory> trajectories,
                       report::RunPreview(panels, flags.options));
  std::optional<report::GnuplotFigure> figure;
  if (!flags.svg.empty()) {
    DCS_ASSIGN_OR_RETURN(figure, PreviewFigure(panels, trajectories, flags));
  }
  DCS_RETURN_IF_ERROR(
      WriteFileAtomically(flags.out, report::PreviewCsv(panels, trajectories, flags.options)));
  std::cerr << "wrote " << trajectories.size() << " trajectories to " << flags.out << std::endl;
  if (figure.has_value()) DCS_RETURN_IF_ERROR(RenderPreviewFigure(*figure, flags));
  return absl::OkStatus();
}

}  // namespace

std::vector<CliCommand> AddScheduleCommands(CLI::App& dcs, const GlobalFlags&) {
  CLI::App* schedule_group = dcs.add_subcommand("schedule", "Schedules: previews");
  schedule_group->require_subcommand(1);
  auto preview_flags = std::make_shared<PreviewFlags>();
  CLI::App* preview = schedule_group->add_subcommand(
      "preview",
      "Write schedule trajectories over a few episodes as CSV (and a figure, drawn by gnuplot)");
  preview->add_option("SPEC,--spec", preview_flags->spec,
                      "a YAML file of schedule configs, a family name, or 'all'")
      ->required();
  preview->add_option("--range", preview_flags->range, "the training range lo,hi")
      ->capture_default_str();
  preview->add_option("--pool-size", preview_flags->options.pool_size,
                      "episode-initial values: pool-N over the range")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  preview->add_option("--episodes", preview_flags->options.episodes, "episodes per schedule")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  preview->add_option("--steps", preview_flags->options.steps, "transitions per episode")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  preview->add_option("--seed", preview_flags->options.seed, "the preview's seed")
      ->capture_default_str();
  AddOutFile(*preview, &preview_flags->out, "the trajectories, a CSV file")->required();
  preview->add_option("--svg", preview_flags->svg,
                      "also draw the figure into this SVG file with gnuplot; its script and data "
                      "stay beside it as STEM.gp and STEM.csv (FILE's stem): restyle the "
                      "script and run `gnuplot STEM.gp` there")
      ->type_name("FILE");

  return {{preview, [preview_flags] {
             const absl::Status status = Preview(*preview_flags);
             return status.ok() ? kExitOk : FailCommand(status);
           }}};
}

}  // namespace dcs::services::cli
