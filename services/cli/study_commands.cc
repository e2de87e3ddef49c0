// Copyright 2026 The DCS Authors.
#include "services/cli/study_commands.h"

#include <google/protobuf/struct.pb.h>

#include <iostream>
#include <memory>
#include <string>

#include "absl/random/random.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "coordinator/run_store.h"
#include "dcs/proto_json.h"
#include "run/search_space_yaml.h"
#include "services/command_line.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

using coordinator::Direction;
using coordinator::RunStore;
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
};

struct TrialFlags {
  std::string study;
  int64_t trial = 0;
  std::string value;
  TrialState state = TrialState::kComplete;
};

absl::StatusOr<std::unique_ptr<RunStore>> OpenStore(const std::string& path) {
  return RunStore::Open(path, coordinator::RunStoreOptions{}, absl::Now());
}

// A trial as JSON: its number, its value once complete, its parameters by name (a categorical
// by its choice's name).
std::string TrialJson(const StudyTrial& trial, const run::SearchSpace& space) {
  google::protobuf::Struct json;
  (*json.mutable_fields())["trial"].set_number_value(static_cast<double>(trial.number));
  if (trial.state == TrialState::kComplete) {
    (*json.mutable_fields())["value"].set_number_value(trial.value);
  }
  auto& params = *(*json.mutable_fields())["params"].mutable_struct_value()->mutable_fields();
  for (const run::SearchParameter& parameter : space.parameters) {
    const auto value = trial.values.find(parameter.name);
    if (value == trial.values.end()) continue;
    if (const auto* choices = std::get_if<run::CategoricalDistribution>(&parameter.distribution)) {
      params[parameter.name].set_string_value(choices->choices[static_cast<size_t>(value->second)]);
    } else {
      params[parameter.name].set_number_value(value->second);
    }
  }
  return ProtoToJson(json);
}

// The study's space, to name its parameters' values.
absl::StatusOr<run::SearchSpace> SpaceOf(RunStore& store, const std::string& study) {
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord record, store.GetStudy(study));
  return run::ParseSearchSpaceYaml(record.submission.space, record.id);
}

absl::Status Create(const CreateFlags& flags, const std::string& store_path) {
  DCS_ASSIGN_OR_RETURN(const std::string space, ReadFile(flags.space));
  // Checked here too, to name the file rather than the store in errors.
  DCS_RETURN_IF_ERROR(run::ParseSearchSpaceYaml(space, flags.space).status());
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<RunStore> store, OpenStore(store_path));
  absl::BitGen random;
  const coordinator::StudySubmission submission{
      .request_id = absl::StrFormat("%016x%016x", absl::Uniform<uint64_t>(random),
                                    absl::Uniform<uint64_t>(random)),
      .name = flags.name,
      .space = space,
      .sampler = flags.sampler,
      .seed = flags.seed,
      .direction = flags.direction,
      .tpe = flags.tpe};
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study,
                       store->CreateStudy(submission, absl::Now()));
  std::cout << study.id << std::endl;
  return absl::OkStatus();
}

absl::Status Ask(const std::string& study, const std::string& store_path) {
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<RunStore> store, OpenStore(store_path));
  DCS_ASSIGN_OR_RETURN(const run::SearchSpace space, SpaceOf(*store, study));
  DCS_ASSIGN_OR_RETURN(const StudyTrial trial, store->AskTrial(study, absl::Now()));
  std::cout << TrialJson(trial, space) << std::endl;
  return absl::OkStatus();
}

absl::Status Tell(const TrialFlags& flags, const std::string& store_path) {
  double value = std::numeric_limits<double>::quiet_NaN();
  if (flags.state == TrialState::kComplete && !absl::SimpleAtod(flags.value, &value)) {
    return absl::InvalidArgumentError(
        flags.value.empty()
            ? "a complete trial needs its VALUE (or --state pruned|failed)"
            : absl::StrCat("VALUE must be a number (or inf, -inf, nan), got '", flags.value, "'"));
  }
  if (flags.state == TrialState::kRunning) {
    return absl::InvalidArgumentError("--state is complete, pruned or failed");
  }
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<RunStore> store, OpenStore(store_path));
  return store->TellTrial(flags.study, flags.trial, flags.state, value, absl::Now()).status();
}

absl::Status Best(const std::string& study, const std::string& store_path) {
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<RunStore> store, OpenStore(store_path));
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord record, store->GetStudy(study));
  if (!record.best.has_value()) {
    return absl::FailedPreconditionError(absl::StrCat(study, " has no complete trial yet"));
  }
  DCS_ASSIGN_OR_RETURN(const run::SearchSpace space,
                       run::ParseSearchSpaceYaml(record.submission.space, record.id));
  std::cout << TrialJson(*record.best, space) << std::endl;
  return absl::OkStatus();
}

int Exit(const absl::Status& status) { return status.ok() ? kExitOk : FailCommand(status); }

}  // namespace

std::vector<CliCommand> AddStudyCommands(CLI::App& dcs, const GlobalFlags&) {
  CLI::App* study =
      dcs.add_subcommand("study", "Ask-and-tell studies (TPE or random search), as Optuna's");
  study->require_subcommand(1);
  auto store = std::make_shared<std::string>();
  const auto add_store = [store](CLI::App* command) {
    command->add_option("--store", *store, "the study's SQLite file (created if missing)")
        ->required();
  };

  auto create_flags = std::make_shared<CreateFlags>();
  CLI::App* create = study->add_subcommand("create", "Create a study and print its id");
  create->add_option("--space", create_flags->space, "the search space (YAML)")->required();
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

  CLI::App* best = study->add_subcommand("best", "Print the best complete trial (JSON)");
  best->add_option("study", *study_id, "the study's id")->required();
  add_store(best);

  return {{create, [=] { return Exit(Create(*create_flags, *store)); }},
          {ask, [=] { return Exit(Ask(*study_id, *store)); }},
          {tell, [=] { return Exit(Tell(*trial_flags, *store)); }},
          {best, [=] { return Exit(Best(*study_id, *store)); }}};
}

}  // namespace dcs::services::cli
