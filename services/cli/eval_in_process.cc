// Copyright 2026 The DCS Authors.
//
// `dcs eval` in `dcs-train`: each RUN's policy evaluated over the grid in this process, on
// every core (actor/context_grid.h), or with --on-actors by the cluster's actors
// (grid_evaluation_client.h); a table or JSON on stdout; with --out, the cells as CSV and
// the generalisation map (report/generalization_map.h) rendered by gnuplot. A RUN that
// names a sweep's condition stands for its completed runs (its seeds): each is evaluated, and
// the condition's cell is their mean, its spread the standard deviation across them.

#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "actor/context_grid.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "common/text_table.h"
#include "dcs/v1/evaluation.pb.h"
#include "env/env_registry.h"
#include "learner/trained_policy.h"
#include "report/generalization_map.h"
#include "services/cli/cluster_client.h"
#include "services/cli/command_output.h"
#include "services/cli/figure_render.h"
#include "services/cli/grid_evaluation_client.h"
#include "services/cli/run_client.h"
#include "services/cli/torch_commands.h"
#include "services/evaluation_grid_proto.h"

namespace dcs::services::cli {
namespace {

// Above this many episodes (cells x episodes x runs), a grid runs only with --yes: a typo in N
// should not start hours of work.
constexpr int64_t kEpisodesWithoutYes = 50'000;

// One run's policy, loaded, and its returns per cell once evaluated.
struct EvaluatedRun {
  std::string name;  // its directory or run id
  learner::TrainedPolicy trained;
  actor::PolicyWeights weights;
  std::vector<actor::ContextResult> cells;
};

// What one RUN argument stands for: one run, or a sweep condition's runs.
struct EvaluatedPolicy {
  std::string name;  // as given
  std::vector<EvaluatedRun> runs;
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

// The completed runs of condition `condition` of sweep `sweep_id` on the cluster, in the mode
// `observe` (may be empty when the condition has one). INVALID_ARGUMENT naming the choices for
// an unknown condition or mode, or a condition in several modes without one;
// FAILED_PRECONDITION if none of its runs has completed.
absl::StatusOr<std::vector<std::string>> ConditionRuns(const std::string& sweep_id,
                                                       const std::string& condition,
                                                       const std::string& observe,
                                                       const GlobalFlags& global) {
  DCS_ASSIGN_OR_RETURN(const v1::GetSweepResponse sweep,
                       GetSweep(CoordinatorAddress(global), sweep_id, global.timeout));
  std::vector<int> trials;
  std::vector<std::string> choices;
  for (int t = 0; t < sweep.sweep().trials_size(); ++t) {
    const v1::Trial& trial = sweep.sweep().trials(t);
    choices.push_back(absl::StrCat(sweep_id, ":", trial.condition(), ":", trial.observe()));
    if (trial.condition() == condition && (observe.empty() || trial.observe() == observe)) {
      trials.push_back(t);
    }
  }
  if (trials.size() != 1) {
    return absl::InvalidArgumentError(absl::StrCat(
        sweep_id, ":", condition, observe.empty() ? "" : ":", observe,
        trials.empty() ? " is no condition of the sweep" : " is in several modes",
        " (choose one of: ", absl::StrJoin(choices, ", "), ")"));
  }
  std::vector<std::string> runs;
  for (const v1::Run& run : sweep.runs()) {
    if (run.has_trial() && run.trial() == trials.front() &&
        run.state() == v1::RUN_STATE_COMPLETED) {
      runs.push_back(run.run_id());
    }
  }
  if (runs.empty()) {
    return absl::FailedPreconditionError(absl::StrCat(
        choices[trials.front()], " has no completed run yet (dcs watch ", sweep_id, ")"));
  }
  return runs;
}

// The runs RUN argument `name` stands for: SWEEP_ID:CONDITION[:OBSERVE], a sweep condition's
// completed runs; otherwise one run, a directory or a run id.
absl::StatusOr<EvaluatedPolicy> LoadPolicy(const std::string& name, const EvalFlags& flags,
                                           const GlobalFlags& global) {
  EvaluatedPolicy policy{.name = name};
  std::vector<std::string> runs = {name};
  const std::vector<std::string> parts = absl::StrSplit(name, ':');
  std::error_code error;
  if ((parts.size() == 2 || parts.size() == 3) && !std::filesystem::is_directory(name, error)) {
    DCS_ASSIGN_OR_RETURN(runs, ConditionRuns(parts[0], parts[1],
                                             parts.size() == 3 ? parts[2] : "", global));
  }
  for (const std::string& run : runs) {
    DCS_ASSIGN_OR_RETURN(policy.runs.emplace_back(), LoadRun(run, flags, global));
  }
  return policy;
}

// On a terminal, a line on stderr rewritten as the actors deliver `run`'s cells; elsewhere
// nothing (logs get the table).
GridProgress CellProgress(const std::string& run) {
  if (!isatty(STDERR_FILENO)) return nullptr;
  return [run](int done, int cells) {
    std::cerr << "\rdcs: " << run << " on the actors: " << done << "/" << cells << " cells"
              << (done == cells ? "\n" : "") << std::flush;
  };
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

// Cell `cell` of `policy`: one run's returns as they are; a condition's, its runs' means, their
// mean and the standard deviation across them, and every episode's return, run after run.
v1::GridCell CellOf(const EvaluatedPolicy& policy, const std::vector<actor::GridAxis>& axes,
                    size_t cell) {
  v1::GridCell out;
  for (const double value : actor::CellValues(axes, cell)) out.add_context(value);
  actor::ContextResult pooled;
  for (const EvaluatedRun& run : policy.runs) {
    const actor::ContextResult& result = run.cells[cell];
    pooled.returns.push_back(result.mean);
    out.add_run_means(result.mean);
    for (const double episode_return : result.returns) out.add_returns(episode_return);
  }
  if (policy.runs.size() == 1) {
    out.set_mean(policy.runs.front().cells[cell].mean);
    out.set_std(policy.runs.front().cells[cell].std);
  } else {
    actor::SummarizeContext(pooled);
    out.set_mean(pooled.mean);
    out.set_std(pooled.std);
  }
  return out;
}

v1::GeneralizationGrid ToProto(const std::vector<EvaluatedPolicy>& policies,
                               const std::vector<actor::GridAxis>& axes, const EvalFlags& flags) {
  v1::GeneralizationGrid grid;
  grid.set_env(policies.front().runs.front().trained.run.spec.env);
  for (const actor::GridAxis& axis : axes) *grid.add_axes() = GridAxisToProto(axis);
  grid.set_episodes(flags.episodes);
  grid.set_seed(flags.seed);
  for (const EvaluatedPolicy& policy : policies) {
    v1::PolicyGrid& out = *grid.add_policies();
    out.set_name(policy.name);
    for (const EvaluatedRun& run : policy.runs) {
      v1::EvaluatedCheckpoint& checkpoint = *out.add_runs();
      checkpoint.set_run(run.name);
      checkpoint.set_checkpoint(
          std::filesystem::path(run.trained.checkpoint_path).filename().string());
      checkpoint.set_step(run.trained.step);
    }
    for (size_t c = 0; c < actor::CellCount(axes); ++c) *out.add_cells() = CellOf(policy, axes, c);
  }
  return grid;
}

// The steps of `policy`'s checkpoints, as a column shows them: "150000", or "3 runs".
std::string StepsOf(const v1::PolicyGrid& policy) {
  if (policy.runs_size() == 1) return absl::StrCat(policy.runs(0).step());
  return absl::StrCat(policy.runs_size(), " runs");
}

// A row per policy and cell: the RUN as given, its step, the axes' values, mean and std.
// `csv`: as CSV, every digit.
std::string CellRows(const v1::GeneralizationGrid& grid, bool csv) {
  std::vector<std::string> header = {csv ? "run" : "RUN", csv ? "step" : "STEP"};
  for (const v1::GridAxis& axis : grid.axes()) header.push_back(axis.feature());
  header.insert(header.end(), {csv ? "mean" : "MEAN", csv ? "std" : "STD"});
  std::vector<std::vector<std::string>> rows = {header};
  for (const v1::PolicyGrid& policy : grid.policies()) {
    for (const v1::GridCell& cell : policy.cells()) {
      std::vector<std::string> row = {csv ? report::CsvField(policy.name()) : policy.name(),
                                      csv ? report::CsvField(StepsOf(policy)) : StepsOf(policy)};
      for (const double value : cell.context()) {
        row.push_back(csv ? report::CsvNumber(value) : absl::StrFormat("%g", value));
      }
      for (const double value : {cell.mean(), cell.std()}) {
        row.push_back(csv ? report::CsvNumber(value) : absl::StrFormat("%.1f", value));
      }
      rows.push_back(std::move(row));
    }
  }
  if (!csv) return RenderTable(rows, std::vector<bool>(header.size(), true));
  std::string text;
  for (const std::vector<std::string>& row : rows) {
    absl::StrAppend(&text, absl::StrJoin(row, ","), "\n");
  }
  return text;
}

// Where `run` trained along `axis`: its varied feature's range and pool, or its value.
report::TrainingSpan TrainingSpanOf(const learner::TrainedPolicy& run,
                                    const actor::GridAxis& axis) {
  const run::RunPlan& plan = run.plan;
  if (axis.feature != plan.feature) {
    const double value = plan.slot.context[axis.feature];
    return {.low = value, .high = value};
  }
  report::TrainingSpan span{.low = run.run.spec.range_lo, .high = run.run.spec.range_hi};
  for (const env::FeaturePool& pool : plan.slot.pools) {
    if (pool.feature == plan.feature) span.pool = pool.pool.values();
  }
  return span;
}

report::GeneralizationMap MapOf(const std::vector<EvaluatedPolicy>& policies,
                                const v1::GeneralizationGrid& grid,
                                const std::vector<actor::GridAxis>& axes) {
  report::GeneralizationMap map{.name = "generalization"};
  for (const actor::GridAxis& axis : axes) {
    report::MapAxis& out = map.axes.emplace_back(report::MapAxis{.feature = axis.name});
    for (int i = 0; i < axis.count; ++i) out.values.push_back(axis.value(i));
  }
  for (size_t p = 0; p < policies.size(); ++p) {
    const v1::PolicyGrid& cells = grid.policies(p);
    report::MapPolicy policy{
        .label = absl::StrCat(std::filesystem::path(cells.name()).filename().string(), " @ ",
                              StepsOf(cells))};
    for (const v1::GridCell& cell : cells.cells()) {
      policy.means.push_back(cell.mean());
      policy.stds.push_back(cell.std());
    }
    // A condition's runs share their config but for the seed: the first's span is theirs.
    for (const actor::GridAxis& axis : axes) {
      policy.training.push_back(TrainingSpanOf(policies[p].runs.front().trained, axis));
    }
    map.policies.push_back(std::move(policy));
  }
  map.title = absl::StrCat(grid.env(), ": mean return per context");
  return map;
}

absl::Status Evaluate(const EvalFlags& flags, const GlobalFlags& global) {
  std::vector<EvaluatedPolicy> policies;
  size_t runs = 0;
  for (const std::string& name : flags.runs) {
    DCS_ASSIGN_OR_RETURN(EvaluatedPolicy policy, LoadPolicy(name, flags, global));
    for (const EvaluatedRun& run : policy.runs) {
      const std::string& env = run.trained.run.spec.env;
      const EvaluatedRun& first = policies.empty() ? policy.runs.front()
                                                   : policies.front().runs.front();
      if (env != first.trained.run.spec.env) {
        return absl::InvalidArgumentError(absl::StrCat(
            run.name, " is a ", env, " run, ", first.name, " a ", first.trained.run.spec.env,
            " run: one grid needs one environment"));
      }
    }
    runs += policy.runs.size();
    policies.push_back(std::move(policy));
  }
  const int threads = flags.threads > 0
                          ? flags.threads
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::vector<actor::GridAxis> axes;
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(
      policies.front().runs.front().trained.run.spec.env, [&]<typename Env>() -> absl::Status {
        DCS_ASSIGN_OR_RETURN(axes, ParseAxes<Env>(flags.grid));
        const int64_t episodes = static_cast<int64_t>(actor::CellCount(axes)) * flags.episodes *
                                 static_cast<int64_t>(runs);
        if (episodes > kEpisodesWithoutYes && !flags.yes) {
          return absl::FailedPreconditionError(absl::StrCat(
              "the grid is ", episodes, " episodes (", actor::CellCount(axes), " cells x ",
              flags.episodes, " episodes x ", runs, " runs), more than ", kEpisodesWithoutYes,
              ": pass --yes to run it"));
        }
        for (EvaluatedPolicy& policy : policies) {
          for (EvaluatedRun& run : policy.runs) {
            if (flags.on_actors) {
              // Every cell checked here, as EvaluateGrid does: an actor cannot refuse one.
              for (size_t cell = 0; cell < actor::CellCount(axes); ++cell) {
                DCS_RETURN_IF_ERROR(
                    actor::GridCellOptions<Env>(run.trained.plan.slot, axes, cell).status());
              }
              DCS_ASSIGN_OR_RETURN(run.cells,
                                   EvaluateGridOnCluster(CoordinatorAddress(global), run.name,
                                                         run.weights, axes, flags.episodes,
                                                         flags.seed, global.timeout,
                                                         CellProgress(run.name)));
              continue;
            }
            DCS_ASSIGN_OR_RETURN(run.cells, actor::EvaluateGrid<Env>(
                                                run.weights, run.trained.plan.slot, axes,
                                                flags.episodes, flags.seed, threads));
          }
        }
        return absl::OkStatus();
      }));
  const v1::GeneralizationGrid grid = ToProto(policies, axes, flags);
  if (!flags.out.empty()) {
    DCS_ASSIGN_OR_RETURN(const report::GnuplotFigure figure,
                         report::GeneralizationMapFigure(MapOf(policies, grid, axes)));
    DCS_ASSIGN_OR_RETURN(const RenderedFigure rendered,
                         RenderFigure(figure, flags.format, flags.out));
    DCS_RETURN_IF_ERROR(
        WriteFileAtomically(absl::StrCat(flags.out, "/cells.csv"), CellRows(grid, true)));
    std::cerr << "dcs: wrote " << rendered.path << " and " << flags.out << "/cells.csv"
              << std::endl;
  }
  std::cout << (global.output == OutputFormat::kJson
                    ? CommandJson(grid) + "\n"
                    : CellRows(grid, /*csv=*/global.output == OutputFormat::kCsv));
  return absl::OkStatus();
}

}  // namespace

int EvaluateInProcess(const EvalFlags& flags, const GlobalFlags& global) {
  if (absl::Status status = Evaluate(flags, global); !status.ok()) return FailCommand(status);
  return 0;
}

}  // namespace dcs::services::cli
