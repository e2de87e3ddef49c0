// Copyright 2026 The DCS Authors.
#include "services/cli/runs_commands.h"

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "services/cli/cluster_client.h"
#include "services/cli/command_output.h"
#include "services/cli/run_client.h"
#include "services/cli/run_follower.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

// Where `dcs runs watch` and `get` put a run's files unless told: <data-dir>/runs/<run id>.
std::string DefaultOut(const GlobalFlags& flags, const std::string& run_id) {
  return flags.data_dir + "/runs/" + run_id;
}

// The cluster's runs, or those of the sweep `sweep_id` if not empty.
absl::StatusOr<std::vector<v1::Run>> RunsToList(const GlobalFlags& flags,
                                                const std::string& sweep_id) {
  if (sweep_id.empty()) return ListRuns(CoordinatorAddress(flags), flags.timeout);
  absl::StatusOr<v1::GetSweepResponse> sweep =
      GetSweep(CoordinatorAddress(flags), sweep_id, flags.timeout);
  if (!sweep.ok()) return sweep.status();
  return std::vector<v1::Run>(sweep->runs().begin(), sweep->runs().end());
}

int ListRunsCommand(const GlobalFlags& flags, const std::string& sweep_id) {
  absl::StatusOr<std::vector<v1::Run>> runs = RunsToList(flags, sweep_id);
  if (!runs.ok()) return FailCommand(runs.status());
  if (flags.output == OutputFormat::kJson) {
    v1::ListRunsResponse response;
    for (const v1::Run& run : *runs) *response.add_runs() = run;
    std::cout << CommandJson(response) << std::endl;
    return kExitOk;
  }
  std::vector<std::vector<std::string>> rows = {
      {"RUN", "STATE", "ENV", "SEED", "STEP", "STEPS/S", "AVG_COMBINED"}};
  for (const v1::Run& run : *runs) {
    const v1::RunProgress& progress = run.progress();
    rows.push_back(
        {run.run_id(), EnumWordOf(run.state()), run.env(), std::to_string(run.seed()),
         absl::StrFormat("%d/%d", progress.timesteps(), progress.total_timesteps()),
         absl::StrFormat("%.0f", progress.steps_per_second()),
         progress.has_avg_combined() ? absl::StrFormat("%.1f", progress.avg_combined()) : "-"});
  }
  std::cout << FormatRows(rows, flags.output) << std::flush;
  return kExitOk;
}

int CancelRunCommand(const GlobalFlags& flags, const std::string& run_id) {
  absl::StatusOr<v1::Run> run = CancelRun(CoordinatorAddress(flags), run_id, flags.timeout);
  if (!run.ok()) return FailCommand(run.status());
  std::cout << (flags.output == OutputFormat::kJson
                    ? CommandJson(*run)
                    : absl::StrCat(run->run_id(), " ", EnumWordOf(run->state())))
            << std::endl;
  return kExitOk;
}

int RemoveRunsCommand(const GlobalFlags& flags, const std::vector<std::string>& run_ids) {
  absl::StatusOr<std::vector<v1::Run>> removed =
      DeleteRuns(CoordinatorAddress(flags), run_ids, flags.timeout);
  if (!removed.ok()) return FailCommand(removed.status());
  if (flags.output == OutputFormat::kJson) {
    v1::DeleteRunsResponse response;
    for (const v1::Run& run : *removed) *response.add_runs() = run;
    std::cout << CommandJson(response) << std::endl;
    return kExitOk;
  }
  for (const v1::Run& run : *removed) std::cout << run.run_id() << " removed" << std::endl;
  return kExitOk;
}

int GetRunCommand(const GlobalFlags& flags, const std::string& run_id, std::string out) {
  if (out.empty()) out = DefaultOut(flags, run_id);
  if (absl::Status status = DownloadRun(CoordinatorAddress(flags), run_id, out, flags.timeout);
      !status.ok()) {
    return FailCommand(status);
  }
  std::cout << out << std::endl;
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddRunsCommands(CLI::App& dcs, const GlobalFlags& flags) {
  CLI::App* runs = dcs.add_subcommand(
      "runs", "The cluster's runs: list them (no subcommand), watch, cancel or get one, "
              "remove ended ones");
  auto run_id = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto sweep_id = std::make_shared<std::string>();
  runs->add_option("--sweep", *sweep_id, "list only this sweep's runs, e.g. sweep-1");

  CLI::App* watch = runs->add_subcommand(
      "watch", "Follow a run to its end (Ctrl-C detaches), then download it and summarise it");
  watch->add_option("run", *run_id, "the run's id, e.g. run-1")->required();
  AddOutDirectory(*watch, out.get(), "where its files go (default: <data-dir>/runs/<run id>)");

  CLI::App* cancel = runs->add_subcommand("cancel", "Stop a queued or running run");
  cancel->add_option("run", *run_id, "the run's id")->required();

  CLI::App* get = runs->add_subcommand(
      "get", "Download a run's config, checkpoints and evaluation log, as `dcs train` lays "
             "them out");
  get->add_option("run", *run_id, "the run's id")->required();
  AddOutDirectory(*get, out.get(), "where its files go (default: <data-dir>/runs/<run id>)");

  auto run_ids = std::make_shared<std::vector<std::string>>();
  CLI::App* rm = runs->add_subcommand(
      "rm", "Remove ended runs for good: their records and files on the coordinator, every one "
            "named or none (a sweep's runs go with their sweep: dcs sweeps rm)");
  rm->add_option("run", *run_ids, "the runs' ids, e.g. run-1 run-2")->required();

  return {
      {watch,
       [&flags, run_id, out] {
         return FollowRun(CoordinatorAddress(flags), *run_id,
                          out->empty() ? DefaultOut(flags, *run_id) : *out, flags);
       },
       kTableOrJson},
      {cancel, [&flags, run_id] { return CancelRunCommand(flags, *run_id); }, kTableOrJson},
      {get, [&flags, run_id, out] { return GetRunCommand(flags, *run_id, *out); }},
      {rm, [&flags, run_ids] { return RemoveRunsCommand(flags, *run_ids); }, kTableOrJson},
      {runs, [&flags, sweep_id] { return ListRunsCommand(flags, *sweep_id); }, kEveryFormat},
  };
}

}  // namespace dcs::services::cli
