// Copyright 2026 The DCS Authors.
#include "services/cli/train_command.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "env/env_registry.h"
#include "run/run_directory.h"
#include "services/cli/cluster_client.h"
#include "services/cli/run_client.h"
#include "services/cli/run_follower.h"
#include "services/cli/torch_commands.h"
#include "services/cli/training_report.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

struct TrainFlags {
  std::string config;
  std::string out;
  uint64_t seed = 0;
  bool seed_given = false;
  bool resume = false;
  int keep = 3;
  bool cluster = false;
};

// The run the flags ask for, checked against its directory; nothing changed yet. A new run
// needs a directory without one; a resumed run needs its stored config, equal to CONFIG if that
// is given too.
absl::StatusOr<run::RunRequest> CheckRunRequest(const TrainFlags& flags,
                                                const GlobalFlags& global) {
  if (flags.resume && flags.config.empty()) {
    if (flags.out.empty()) {
      return UsageError("--resume needs --out (the run's directory) or the run config");
    }
    return run::StoredRun(flags.out);
  }
  if (flags.config.empty()) {
    return UsageError("a run config is required: dcs train CONFIG (or --resume --out DIR)");
  }
  absl::StatusOr<std::string> text = ReadFile(flags.config);
  if (!text.ok()) {
    return absl::NotFoundError(absl::StrCat("cannot read the run config ", flags.config));
  }
  DCS_ASSIGN_OR_RETURN(
      run::RunRequest request,
      run::RequestRun(flags.seed_given ? run::ConfigWithSeed(*text, flags.seed) : *std::move(text),
                      flags.config, flags.out, global.data_dir));
  if (flags.resume) {
    DCS_RETURN_IF_ERROR(run::CheckResumedRun(
        request, flags.seed_given ? absl::StrCat(flags.config, " with --seed") : flags.config));
  } else if (absl::Status fresh = run::CheckNewRun(request); !fresh.ok()) {
    return absl::Status(fresh.code(),
                        absl::StrCat(fresh.message(), ": pass --resume to continue it, or --out "
                                                      "for a new directory"));
  }
  return request;
}

// The run submitted to the cluster, followed to its end and downloaded into its directory;
// checked here first, as in process, for quick feedback (the coordinator checks again).
int RunTrainOnCluster(const TrainFlags& flags, const GlobalFlags& global,
                      const run::RunRequest& request) {
  const std::string address = CoordinatorAddress(global);
  absl::StatusOr<std::string> text = ReadFile(flags.config);
  if (!text.ok()) return FailCommand(text.status());
  absl::StatusOr<v1::Run> run =
      SubmitRun(address, *text, flags.config,
                flags.seed_given ? std::optional<uint64_t>(flags.seed) : std::nullopt,
                global.timeout);
  if (!run.ok()) return FailCommand(run.status());
  std::cerr << "dcs: submitted " << run->run_id() << " to " << address << std::endl;
  return FollowRun(address, run->run_id(), request.dir, global);
}

int RunTrain(const TrainFlags& flags, const GlobalFlags& global) {
  if (flags.cluster && flags.resume) {
    return FailCommand(
        UsageError("--resume is for runs in this process; a cluster resumes its runs itself "
                   "(dcs runs)"));
  }
  absl::StatusOr<run::RunRequest> request = CheckRunRequest(flags, global);
  if (!request.ok()) return FailCommand(request.status());
  if (flags.cluster) return RunTrainOnCluster(flags, global, *request);
  return TrainInProcess(*request, flags.resume, flags.keep, global);
}

}  // namespace

std::vector<CliCommand> AddTrainCommand(CLI::App& dcs, const GlobalFlags& flags) {
  auto train_flags = std::make_shared<TrainFlags>();
  CLI::App* train = dcs.add_subcommand(
      "train", "Train one run of a config (PPO, with the paper's evaluation) in this process, "
             "or on a cluster");
  train->add_option("CONFIG,--config", train_flags->config,
                    "the run config (YAML; examples in configs/, every key in docs/config.md)")
      ->type_name("FILE");
  AddOutDirectory(*train, &train_flags->out,
                  "the run's directory: checkpoints, evaluations.csv and .json (default: "
                  "<data-dir>/runs/<config name>-seed<seed>)");
  train->add_option("--seed", train_flags->seed, "the run's seed, instead of the config's")
      ->each([train_flags](const std::string&) { train_flags->seed_given = true; });
  train->add_flag("--resume", train_flags->resume,
                  "continue the run in --out (or CONFIG's default directory) from its "
                  "latest checkpoint");
  train->add_option("--keep", train_flags->keep, "checkpoints to keep")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  train->add_flag("--cluster", train_flags->cluster,
                  "submit the run to the cluster at --addr (default: the local cluster of "
                  "`dcs up`), follow it (Ctrl-C detaches; the run goes on), then download it "
                  "into --out");
  return {{train, [train_flags, &flags] { return RunTrain(*train_flags, flags); }, kTableOrJson}};
}

}  // namespace dcs::services::cli
