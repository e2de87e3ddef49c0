// Copyright 2026 The DCS Authors.
//
// `dcs eval` in `dcs-train`: each RUN's policy evaluated over the grid in this process, on
// every core (actor/context_grid.h), or with --on-actors by the cluster's actors; a table or
// JSON on stdout; with --out, the cells as CSV and the generalisation map
// (coordinator/generalization_map.h) rendered by gnuplot.

#include <filesystem>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "actor/context_grid.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "common/text_table.h"
#include "coordinator/generalization_map.h"
#include "dcs/proto_json.h"
#include "dcs/v1/evaluation.pb.h"
#include "env/env_registry.h"
#include "learner/trained_policy.h"
#include "services/cli/cluster_client.h"
#include "services/cli/figure_render.h"
#include "services/cli/grid_evaluation_client.h"
#include "services/cli/torch_commands.h"

namespace dcs::services::cli {
namespace {

// Above this many episodes (cells x episodes x runs), a grid runs only with --yes: a typo in N
// should not start hours of work.
constexpr int64_t kEpisodesWithoutYes = 50'000;

// One RUN's policy, loaded.
struct EvaluatedRun {
  std::string name;  // as given
  learner::TrainedPolicy trained;
  actor::PolicyWeights weights;
  std::vector<actor::ContextResult> cells;
};

absl::StatusOr<EvaluatedRun> LoadRun(const std::string& name, const EvalFlags& flags,
                                     const GlobalFlags& global) {
  DCS_ASSIGN_OR_RETURN(const LocalRun local, LocalRun::Find(name, global));
  if (flags.on_actors && !local.on_cluster()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "--on-actors evaluates runs of the cluster; ", name,
        " is a directory here: evaluate it in this process (without --on-actors)"));
  }
  DCS_ASSIGN_OR_RETURN(learner::TrainedPolicy trained,
                       learner::LoadTrainedPolicy(local.dir(), flags.checkpoint));
  actor::PolicyWeights weights = trained.learner->ActorWeights();
  return EvaluatedRun{.name = name, .trained = std::move(trained), .weights = std::move(weights)};
}

// The grid's axes, parsed against `Env`'s features: one or two, of different features.
template <typename Env>
absl::StatusOr<std::vector<actor::GridAxis>> ParseAxes(const std::vector<std::string>& grid) {
  if (grid.empty() || grid.size() > 2) {
    return absl::InvalidArgumentError(
        "--grid is given once (a line per run) or twice (a heatmap per run)");
  }
  std::vector<actor::GridAxis> axes;
  for (const std::string& text : grid) {
    DCS_ASSIGN_OR_RETURN(actor::GridAxis axis, actor::ParseGridAxis(Env::Features(), text));
    if (!axes.empty() && axes.front().feature == axis.feature) {
      return absl::InvalidArgumentError(
          absl::StrCat("--grid names feature '", axis.name, "' twice"));
    }
    axes.push_back(std::move(axis));
  }
  return axes;
}

v1::GeneralizationGrid ToProto(const std::vector<EvaluatedRun>& runs,
                               const std::vector<actor::GridAxis>& axes, const EvalFlags& flags) {
  v1::GeneralizationGrid grid;
  grid.set_env(runs.front().trained.run.spec.env);
  for (const actor::GridAxis& axis : axes) {
    v1::GridAxis& out = *grid.add_axes();
    out.set_feature(axis.name);
    out.set_low(axis.low);
    out.set_high(axis.high);
    out.set_count(axis.count);
  }
  grid.set_episodes(flags.episodes);
  grid.set_seed(flags.seed);
  for (const EvaluatedRun& run : runs) {
    v1::PolicyGrid& policy = *grid.add_policies();
    policy.set_run(run.name);
    policy.set_checkpoint(
        std::filesystem::path(run.trained.checkpoint_path).filename().string());
    policy.set_step(run.trained.step);
    for (size_t c = 0; c < run.cells.size(); ++c) {
      v1::GridCell& cell = *policy.add_cells();
      for (const double value : actor::CellValues(axes, c)) cell.add_context(value);
      cell.set_mean(run.cells[c].mean);
      cell.set_std(run.cells[c].std);
      for (const double episode_return : run.cells[c].returns) cell.add_returns(episode_return);
    }
  }
  return grid;
}

// A row per run and cell: the run, the axes' values, mean and std. `csv`: as CSV, every digit.
std::string CellRows(const v1::GeneralizationGrid& grid, bool csv) {
  std::vector<std::string> header = {csv ? "run" : "RUN", csv ? "step" : "STEP"};
  for (const v1::GridAxis& axis : grid.axes()) header.push_back(axis.feature());
  header.insert(header.end(), {csv ? "mean" : "MEAN", csv ? "std" : "STD"});
  std::vector<std::vector<std::string>> rows = {header};
  for (const v1::PolicyGrid& policy : grid.policies()) {
    for (const v1::GridCell& cell : policy.cells()) {
      std::vector<std::string> row = {csv ? coordinator::CsvField(policy.run()) : policy.run(),
                                      absl::StrCat(policy.step())};
      for (const double value : cell.context()) {
        row.push_back(csv ? coordinator::CsvNumber(value) : absl::StrFormat("%g", value));
      }
      for (const double value : {cell.mean(), cell.std()}) {
        row.push_back(csv ? coordinator::CsvNumber(value) : absl::StrFormat("%.1f", value));
      }
      rows.push_back(std::move(row));
    }
  }
  if (!csv) return RenderTable(rows, std::vector<bool>(header.size(), true));
  std::string text;
  for (const std::vector<std::string>& row : rows) absl::StrAppend(&text, absl::StrJoin(row, ","),
                                                                   "\n");
  return text;
}

// Where `run` trained along `axis`: its varied feature's range and pool, or its value.
coordinator::TrainingSpan TrainingSpanOf(const learner::TrainedPolicy& run,
                                         const actor::GridAxis& axis) {
  const run::RunPlan& plan = run.plan;
  if (axis.feature != plan.feature) {
    const double value = plan.slot.context[axis.feature];
    return {.low = value, .high = value};
  }
  coordinator::TrainingSpan span{.low = run.run.spec.range_lo, .high = run.run.spec.range_hi};
  for (const env::FeaturePool& pool : plan.slot.pools) {
    if (pool.feature == plan.feature) span.pool = pool.pool.values();
  }
  return span;
}

coordinator::GeneralizationMap MapOf(const std::vector<EvaluatedRun>& runs,
                                     const std::vector<actor::GridAxis>& axes) {
  coordinator::GeneralizationMap map{.name = "generalization"};
  for (const actor::GridAxis& axis : axes) {
    coordinator::MapAxis& out = map.axes.emplace_back(coordinator::MapAxis{.feature = axis.name});
    for (int i = 0; i < axis.count; ++i) out.values.push_back(axis.value(i));
  }
  for (const EvaluatedRun& run : runs) {
    coordinator::MapPolicy policy{
        .label = absl::StrCat(std::filesystem::path(run.name).filename().string(), " @ ",
                              run.trained.step)};
    for (const actor::ContextResult& cell : run.cells) {
      policy.means.push_back(cell.mean);
      policy.stds.push_back(cell.std);
    }
    for (const actor::GridAxis& axis : axes) {
      policy.training.push_back(TrainingSpanOf(run.trained, axis));
    }
    map.policies.push_back(std::move(policy));
  }
  map.title = absl::StrCat(runs.front().trained.run.spec.env, ": mean return per context");
  return map;
}

absl::Status Evaluate(const EvalFlags& flags, const GlobalFlags& global) {
  std::vector<EvaluatedRun> runs;
  for (const std::string& name : flags.runs) {
    DCS_ASSIGN_OR_RETURN(EvaluatedRun run, LoadRun(name, flags, global));
    if (!runs.empty() && run.trained.run.spec.env != runs.front().trained.run.spec.env) {
      return absl::InvalidArgumentError(absl::StrCat(
          name, " is a ", run.trained.run.spec.env, " run, ", runs.front().name, " a ",
          runs.front().trained.run.spec.env, " run: one grid needs one environment"));
    }
    runs.push_back(std::move(run));
  }
  const int threads = flags.threads > 0
                          ? flags.threads
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::vector<actor::GridAxis> axes;
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(
      runs.front().trained.run.spec.env, [&]<typename Env>() -> absl::Status {
        DCS_ASSIGN_OR_RETURN(axes, ParseAxes<Env>(flags.grid));
        const int64_t episodes = static_cast<int64_t>(actor::CellCount(axes)) * flags.episodes *
                                 static_cast<int64_t>(runs.size());
        if (episodes > kEpisodesWithoutYes && !flags.yes) {
          return absl::FailedPreconditionError(absl::StrCat(
              "the grid is ", episodes, " episodes (", actor::CellCount(axes), " cells x ",
              flags.episodes, " episodes x ", runs.size(), " runs), more than ",
              kEpisodesWithoutYes, ": pass --yes to run it"));
        }
        for (EvaluatedRun& run : runs) {
          if (flags.on_actors) {
            // Every cell checked here, as EvaluateGrid does: an actor cannot refuse one.
            for (size_t cell = 0; cell < actor::CellCount(axes); ++cell) {
              DCS_RETURN_IF_ERROR(
                  actor::GridCellOptions<Env>(run.trained.plan.slot, axes, cell).status());
            }
            DCS_ASSIGN_OR_RETURN(run.cells, EvaluateGridOnCluster(CoordinatorAddress(global),
                                                                  run.name, run.weights, axes,
                                                                  flags.episodes, flags.seed,
                                                                  global.timeout));
            continue;
          }
          DCS_ASSIGN_OR_RETURN(run.cells, actor::EvaluateGrid<Env>(run.weights,
                                                                   run.trained.plan.slot, axes,
                                                                   flags.episodes, flags.seed,
                                                                   threads));
        }
        return absl::OkStatus();
      }));
  const v1::GeneralizationGrid grid = ToProto(runs, axes, flags);
  if (!flags.out.empty()) {
    DCS_ASSIGN_OR_RETURN(const coordinator::GnuplotFigure figure,
                         coordinator::GeneralizationMapFigure(MapOf(runs, axes)));
    DCS_ASSIGN_OR_RETURN(const RenderedFigure rendered,
                         RenderFigure(figure, flags.format, flags.out));
    DCS_RETURN_IF_ERROR(
        WriteFileAtomically(absl::StrCat(flags.out, "/cells.csv"), CellRows(grid, true)));
    std::cerr << "dcs: wrote " << rendered.path << " and " << flags.out << "/cells.csv"
              << std::endl;
  }
  std::cout << (global.output == OutputFormat::kJson ? ProtoToJson(grid) + "\n"
                                                      : CellRows(grid, false));
  return absl::OkStatus();
}

}  // namespace

int EvaluateInProcess(const EvalFlags& flags, const GlobalFlags& global) {
  if (absl::Status status = Evaluate(flags, global); !status.ok()) return FailCommand(status);
  return 0;
}

}  // namespace dcs::services::cli
