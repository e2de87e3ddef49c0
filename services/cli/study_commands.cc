// Copyright 2026 The DCS Authors.
#include "services/cli/study_commands.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <string>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "common/text_table.h"
#include "coordinator/study_table.h"
#include "dcs/v1/study.pb.h"
#include "report/study_figures.h"
#include "run/search_space_yaml.h"
#include "services/cli/cluster_client.h"
#include "services/cli/command_output.h"
#include "services/cli/figure_render.h"
#include "services/cli/run_client.h"
#include "services/cli/study_client.h"
#include "services/coordinator/study_proto.h"
#include "services/command_line.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

using coordinator::Direction;
using coordinator::SamplerKind;
using coordinator::StudyTrial;
using coordinator::TrialState;

struct CreateFlags {
  std::string space;
  std::string name;
  SamplerKind sampler = SamplerKind::kTpe;
  uint64_t seed = 0;
  Direction direction = Direction::kMinimize;
  coordinator::TpeOptions tpe;
  coordinator::PrunerOptions pruner;
};

struct TrialFlags {
  std::string study;
  int64_t trial = 0;
  int64_t step = 0;  // for report
  std::string value;
  TrialState state = TrialState::kComplete;
};

// A value given on the command line: a number, inf, -inf or nan.
absl::StatusOr<double> ParseValue(const std::string& text) {
  double value = 0;
  if (!absl::SimpleAtod(text, &value)) {
    return absl::InvalidArgumentError(
        absl::StrCat("VALUE must be a number (or inf, -inf, nan), got '", text, "'"));
  }
  return value;
}

// The studies of --store, or else of the coordinator (--addr, or the local cluster's).
absl::StatusOr<std::unique_ptr<StudyClient>> Studies(const std::string& store,
                                                     MissingStore missing,
                                                     const GlobalFlags& flags) {
  if (!store.empty()) return OpenLocalStudies(store, missing);
  return ConnectStudies(CoordinatorAddress(flags), flags.timeout);
}

// A trial as one line of JSON (dcs.v1.StudyTrialLine).
std::string TrialJson(const StudyTrial& trial, const run::SearchSpace& space) {
  v1::StudyTrialLine line;
  line.set_trial(static_cast<int32_t>(trial.number));
  line.set_state(std::string(NameOf(coordinator::kTrialStateNames, trial.state)));
  if (trial.state == TrialState::kComplete) line.set_value(trial.value);
  auto& params = *line.mutable_params()->mutable_fields();
  for (const run::SearchParameter& parameter : space.parameters) {
    const auto value = trial.values.find(parameter.name);
    if (value == trial.values.end()) continue;
    const auto* choices = std::get_if<run::CategoricalDistribution>(&parameter.distribution);
    if (choices == nullptr) {
      params[parameter.name].set_number_value(value->second);
    } else {
      params[parameter.name].set_string_value(run::ChoiceOf(*choices, value->second));
    }
  }
  return CommandJson(line);
}

// The study's space, to name its parameters' values.
absl::StatusOr<run::SearchSpace> SpaceOf(const coordinator::StudyRecord& study) {
  return run::ParseSearchSpaceYaml(study.submission.space, study.id);
}

// The space of `studies create SPACE`, checked here first, to name the file in errors, and
// before a store is made for a study that cannot be.
absl::StatusOr<std::string> ReadSpace(const CreateFlags& flags) {
  DCS_ASSIGN_OR_RETURN(std::string space, ReadFile(flags.space));
  DCS_RETURN_IF_ERROR(run::ParseSearchSpaceYaml(space, flags.space).status());
  return space;
}

absl::Status Create(const CreateFlags& flags, const std::string& space, StudyClient& studies) {
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study,
                       studies.Create({.request_id = NewRequestId(),
                                       .name = flags.name,
                                       .space = space,
                                       .sampler = flags.sampler,
                                       .seed = flags.seed,
                                       .direction = flags.direction,
                                       .tpe = flags.tpe,
                                       .pruner = flags.pruner}));
  std::cout << study.id << std::endl;
  return absl::OkStatus();
}

absl::Status Ask(const std::string& study_id, StudyClient& studies) {
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study, studies.Get(study_id));
  DCS_ASSIGN_OR_RETURN(const run::SearchSpace space, SpaceOf(study));
  DCS_ASSIGN_OR_RETURN(const StudyTrial trial, studies.Ask(study_id, NewRequestId()));
  std::cout << TrialJson(trial, space) << std::endl;
  return absl::OkStatus();
}

absl::Status Tell(const TrialFlags& flags, StudyClient& studies) {
  if (flags.state == TrialState::kRunning) {
    return absl::InvalidArgumentError("--state is complete, pruned or failed");
  }
  double value = std::numeric_limits<double>::quiet_NaN();
  if (flags.state == TrialState::kComplete) {
    if (flags.value.empty()) {
      return absl::InvalidArgumentError(
          "a complete trial needs its VALUE (or --state pruned|failed)");
    }
    DCS_ASSIGN_OR_RETURN(value, ParseValue(flags.value));
  }
  return studies.Tell(flags.study, flags.trial, flags.state, value).status();
}

absl::Status Report(const TrialFlags& flags, StudyClient& studies) {
  DCS_ASSIGN_OR_RETURN(const double value, ParseValue(flags.value));
  DCS_ASSIGN_OR_RETURN(const bool prune,
                       studies.Report(flags.study, flags.trial, flags.step, value));
  std::cout << (prune ? "prune" : "continue") << std::endl;
  return absl::OkStatus();
}

absl::Status Best(const std::string& study_id, StudyClient& studies) {
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study, studies.Get(study_id));
  if (!study.best.has_value()) {
    return absl::FailedPreconditionError(absl::StrCat(study_id, " has no complete trial yet"));
  }
  DCS_ASSIGN_OR_RETURN(const run::SearchSpace space, SpaceOf(study));
  std::cout << TrialJson(*study.best, space) << std::endl;
  return absl::OkStatus();
}

// The study's trials: a table (a column per parameter, in the space's order), or with -o json one
// JSON line per trial.
absl::Status Trials(const std::string& study_id, const GlobalFlags& flags, StudyClient& studies) {
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study, studies.Get(study_id));
  DCS_ASSIGN_OR_RETURN(const run::SearchSpace space, SpaceOf(study));
  DCS_ASSIGN_OR_RETURN(const std::vector<StudyTrial> trials, studies.Trials(study_id));
  if (flags.output == OutputFormat::kJson) {
    for (const StudyTrial& trial : trials) std::cout << TrialJson(trial, space) << "\n";
    std::cout << std::flush;
    return absl::OkStatus();
  }
  std::vector<std::vector<std::string>> rows = {{"TRIAL", "STATE", "VALUE"}};
  for (const run::SearchParameter& parameter : space.parameters) {
    rows[0].push_back(parameter.name);
  }
  for (const StudyTrial& trial : trials) {
    std::vector<std::string>& row = rows.emplace_back();
    row = {absl::StrCat(trial.number),
           std::string(NameOf(coordinator::kTrialStateNames, trial.state)),
           std::isnan(trial.value) ? "-" : absl::StrFormat("%.6g", trial.value)};
    for (const run::SearchParameter& parameter : space.parameters) {
      const auto value = trial.values.find(parameter.name);
      const auto* choices = std::get_if<run::CategoricalDistribution>(&parameter.distribution);
      row.push_back(value == trial.values.end() ? "-"
                    : choices != nullptr        ? run::ChoiceOf(*choices, value->second)
                                                : absl::StrFormat("%.6g", value->second));
    }
  }
  std::cout << FormatRows(rows, flags.output) << std::flush;
  return absl::OkStatus();
}

// Every study: a row each with its trials by state and its best value, or with -o json the
// studies as the coordinator answers them.
absl::Status List(const GlobalFlags& flags, StudyClient& studies) {
  DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::StudyRecord> all, studies.List());
  if (flags.output == OutputFormat::kJson) {
    v1::ListStudiesResponse response;
    for (const coordinator::StudyRecord& study : all) *response.add_studies() = StudyToProto(study);
    std::cout << CommandJson(response) << std::endl;
    return absl::OkStatus();
  }
  std::vector<std::vector<std::string>> rows = {
      {"STUDY", "NAME", "DIRECTION", "SAMPLER", "TRIALS"}};
  for (const EnumName<TrialState>& state : coordinator::kTrialStateNames) {
    rows[0].push_back(absl::AsciiStrToUpper(state.name));
  }
  rows[0].insert(rows[0].end(), {"BEST", "SWEEP"});
  for (const coordinator::StudyRecord& study : all) {
    std::vector<std::string>& row = rows.emplace_back();
    int64_t total = 0;
    for (const auto& [state, count] : study.trials_by_state) total += count;
    row = {study.id, study.submission.name.empty() ? "-" : study.submission.name,
           std::string(NameOf(coordinator::kDirectionNames, study.submission.direction)),
           std::string(NameOf(coordinator::kSamplerKindNames, study.submission.sampler)),
           absl::StrCat(total)};
    for (const EnumName<TrialState>& state : coordinator::kTrialStateNames) {
      const auto counted = std::find_if(
          study.trials_by_state.begin(), study.trials_by_state.end(),
          [&](const std::pair<TrialState, int64_t>& entry) { return entry.first == state.value; });
      row.push_back(absl::StrCat(counted == study.trials_by_state.end() ? 0 : counted->second));
    }
    row.push_back(study.best.has_value() ? absl::StrFormat("%.6g", study.best->value) : "-");
    row.push_back(study.sweep_id.empty() ? "-" : study.sweep_id);
  }
  std::cout << FormatRows(rows, flags.output) << std::flush;
  return absl::OkStatus();
}

struct PlotFlags {
  std::string study;
  std::string out;
  report::FigureFormat format = report::FigureFormat::kSvg;
};

// The study's optimisation history drawn by gnuplot into --out (default
// <data-dir>/reports/<study id>), beside its data and script.
absl::Status Plot(const PlotFlags& flags, const GlobalFlags& global, StudyClient& studies) {
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study, studies.Get(flags.study));
  DCS_ASSIGN_OR_RETURN(const std::vector<StudyTrial> trials, studies.Trials(flags.study));
  DCS_ASSIGN_OR_RETURN(const report::GnuplotFigure figure,
                       report::StudyHistoryFigure(study, trials));
  DCS_ASSIGN_OR_RETURN(
      const RenderedFigure rendered,
      RenderFigure(figure, flags.format,
                   flags.out.empty() ? absl::StrCat(global.data_dir, "/reports/", flags.study)
                                     : flags.out));
  if (!rendered.gnuplot_output.empty()) std::cerr << rendered.gnuplot_output << std::endl;
  std::cout << rendered.path << std::endl;
  return absl::OkStatus();
}

// Runs `command` on the studies of --store or the coordinator; the exit code.
template <typename Command>
int RunOn(const std::string& store, MissingStore missing, const GlobalFlags& flags,
          const Command& command) {
  absl::StatusOr<std::unique_ptr<StudyClient>> studies = Studies(store, missing, flags);
  if (!studies.ok()) return FailCommand(studies.status());
  const absl::Status status = command(**studies);
  return status.ok() ? kExitOk : FailCommand(status);
}

}  // namespace

std::vector<CliCommand> AddStudyCommands(CLI::App& dcs, const GlobalFlags& flags) {
  // Spelt as `runs` and `sweeps` are, and as first spelt, `study`.
  CLI::App* study = dcs.add_subcommand(
      "studies", "Ask-and-tell studies (TPE or random search), as Optuna's: list them (no "
                 "subcommand), create one, ask, tell, report, best, trials, plot");
  study->alias("study");
  study->require_subcommand(0, 1);
  auto store = std::make_shared<std::string>();
  const auto add_store = [store](CLI::App* command) {
    command->add_option("--store", *store,
                        "keep the study in this SQLite file rather than on the coordinator "
                        "(`studies create` makes it if missing)");
  };
  add_store(study);

  auto create_flags = std::make_shared<CreateFlags>();
  CLI::App* create = study->add_subcommand("create", "Create a study and print its id");
  create->add_option("SPACE,--space", create_flags->space, "the search space (YAML)")
      ->type_name("FILE")
      ->required();
  create->add_option("--name", create_flags->name, "a name for people");
  AddChoiceOption(*create, "--sampler", &create_flags->sampler,
                  ChoicesOf(coordinator::kSamplerKindNames), "tpe (default) or random");
  create->add_option("--seed", create_flags->seed, "the sampler's seed (default 0)");
  AddChoiceOption(*create, "--direction", &create_flags->direction,
                  ChoicesOf(coordinator::kDirectionNames), "minimize (default) or maximize");
  create->add_flag("--multivariate", create_flags->tpe.parzen.multivariate,
                   "TPE samples parameters jointly");
  create->add_flag("--group", create_flags->tpe.group,
                   "with --multivariate: per group of parameters that occur together");
  create->add_flag("--constant-liar", create_flags->tpe.constant_liar,
                   "TPE counts running trials as poor ones, to spread trials asked at once");
  create->add_option("--startup-trials", create_flags->tpe.startup_trials,
                     "random trials before TPE models (default 10)");
  AddChoiceOption(*create, "--pruner", &create_flags->pruner.kind,
                  ChoicesOf(coordinator::kPrunerKindNames),
                  "stop poor trials early at their reports: none (default), median or "
                  "successive_halving");
  create->add_option("--pruner-startup-trials", create_flags->pruner.median.startup_trials,
                     "median: complete trials before any is pruned (default 5)");
  create->add_option("--pruner-warmup-steps", create_flags->pruner.median.warmup_steps,
                     "median: steps before a trial may be pruned (default 0)");
  create->add_option_function<int64_t>(
      "--min-resource",
      [create_flags](int64_t steps) { create_flags->pruner.halving.min_resource = steps; },
      "successive_halving: the step of the first rung (default: auto)");
  create->add_option("--reduction-factor", create_flags->pruner.halving.reduction_factor,
                     "successive_halving: 1 in this many goes on at each rung (default 4)");
  add_store(create);

  auto study_id = std::make_shared<std::string>();
  CLI::App* ask = study->add_subcommand("ask", "Start a trial and print its parameters (JSON)");
  ask->add_option("study", *study_id, "the study's id")->required();
  add_store(ask);

  auto trial_flags = std::make_shared<TrialFlags>();
  CLI::App* tell = study->add_subcommand("tell", "Finish a trial with its objective value");
  tell->add_option("study", trial_flags->study, "the study's id")->required();
  tell->add_option("trial", trial_flags->trial, "the trial's number")->required();
  tell->add_option("value", trial_flags->value, "its objective value (inf, -inf; nan fails it)");
  AddChoiceOption(*tell, "--state", &trial_flags->state, ChoicesOf(coordinator::kTrialStateNames),
                  "complete (default), pruned or failed");
  add_store(tell);

  CLI::App* report = study->add_subcommand(
      "report", "Record a running trial's intermediate value; print prune or continue");
  report->add_option("study", trial_flags->study, "the study's id")->required();
  report->add_option("trial", trial_flags->trial, "the trial's number")->required();
  report->add_option("step", trial_flags->step, "the step it reports at")->required();
  report->add_option("value", trial_flags->value, "its intermediate value")->required();
  add_store(report);

  CLI::App* trials = study->add_subcommand("trials", "List the study's trials and their values");
  trials->add_option("study", *study_id, "the study's id")->required();
  add_store(trials);

  auto plot_flags = std::make_shared<PlotFlags>();
  CLI::App* plot = study->add_subcommand(
      "plot", "Draw the study's optimisation history with gnuplot; print the image's path");
  plot->add_option("study", plot_flags->study, "the study's id")->required();
  AddOutDirectory(*plot, &plot_flags->out,
                  "the directory to write (default: <data-dir>/reports/<study id>)");
  AddChoiceOption(*plot, "--format", &plot_flags->format, ChoicesOf(report::kFigureFormatNames),
                  "svg, png or pdf");
  add_store(plot);

  CLI::App* list_studies = study->add_subcommand(
      "list", "List the studies: direction, sampler, trials by state, the best value (as `dcs "
              "studies` alone)");
  add_store(list_studies);

  CLI::App* best = study->add_subcommand("best", "Print the best complete trial (JSON)");
  best->add_option("study", *study_id, "the study's id")->required();
  add_store(best);

  // Each command runs on the studies of --store or of the coordinator.
  const auto on_studies = [store, &flags](auto command,
                                          MissingStore missing = MissingStore::kRefuse) {
    return [store, &flags, command, missing] { return RunOn(*store, missing, flags, command); };
  };
  const std::function<int()> list =
      on_studies([&flags](StudyClient& s) { return List(flags, s); });
  return {{create,
           [=, &flags] {
             const absl::StatusOr<std::string> space = ReadSpace(*create_flags);
             if (!space.ok()) return FailCommand(space.status());
             return RunOn(*store, MissingStore::kCreate, flags, [&](StudyClient& s) {
               return Create(*create_flags, *space, s);
             });
           }},
          {ask, on_studies([=](StudyClient& s) { return Ask(*study_id, s); }), kTableOrJson},
          {tell, on_studies([=](StudyClient& s) { return Tell(*trial_flags, s); })},
          {report, on_studies([=](StudyClient& s) { return Report(*trial_flags, s); })},
          {trials,
           on_studies([=, &flags](StudyClient& s) { return Trials(*study_id, flags, s); }),
           kEveryFormat},
          {plot, on_studies([=, &flags](StudyClient& s) { return Plot(*plot_flags, flags, s); })},
          {best, on_studies([=](StudyClient& s) { return Best(*study_id, s); }), kTableOrJson},
          {list_studies, list, kEveryFormat},
          {study, list, kEveryFormat}};
}

}  // namespace dcs::services::cli
