// Copyright 2026 The DCS Authors.
#include "services/cli/train_command.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "dcs/proto_json.h"
#include "dcs/v1/evaluation.pb.h"
#include "env/env_registry.h"
#include "learner/torch_runtime.h"
#include "learner/training_run.h"
#include "run/evaluation_log.h"
#include "run/run_directory.h"
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
};

// Set by SIGINT and SIGTERM: the run stops after its current update, with a checkpoint.
std::atomic<bool> stop_requested{false};
extern "C" void RequestStop(int) { stop_requested = true; }

// The run the flags ask for, checked against its directory; nothing changed yet. A new run
// needs a directory without one; a resumed run needs its stored config, equal to --config if
// that is given too.
absl::StatusOr<run::RunRequest> CheckRunRequest(const TrainFlags& flags,
                                                const GlobalFlags& global) {
  if (flags.resume && flags.config.empty()) {
    if (flags.out.empty()) {
      return absl::InvalidArgumentError("--resume needs --out (the run's directory) or --config");
    }
    return run::StoredRun(flags.out);
  }
  if (flags.config.empty()) return absl::InvalidArgumentError("--config is required");
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

std::string FormatEvaluation(const actor::EvaluationResult& evaluation) {
  return absl::StrFormat("eval@%d %.1f", evaluation.step, evaluation.avg_combined);
}

// On a terminal, one line rewritten after every update; otherwise a line per evaluation.
class ProgressPrinter {
 public:
  ProgressPrinter() : terminal_(isatty(STDERR_FILENO) == 1) {}

  void Update(const learner::TrainingProgress& p) {
    const bool new_evaluation = p.evaluation != nullptr && p.evaluation != last_evaluation_;
    last_evaluation_ = p.evaluation;
    if (!terminal_ && !new_evaluation) return;
    const int64_t shown = std::min(p.timesteps, p.total_timesteps);
    std::string line = absl::StrFormat(
        "step %d/%d (%d%%)  %.0f steps/s  return %.1f", p.timesteps, p.total_timesteps,
        shown * 100 / p.total_timesteps, p.steps_per_second, p.recent_return);
    if (p.evaluation != nullptr) absl::StrAppend(&line, "  ", FormatEvaluation(*p.evaluation));
    if (terminal_) {
      std::cerr << "\r\033[K" << line << std::flush;
    } else {
      std::cerr << line << std::endl;
    }
  }

  void Finish() {
    if (terminal_) std::cerr << std::endl;
  }

 private:
  const bool terminal_;
  const actor::EvaluationResult* last_evaluation_ = nullptr;
};

void PrintSummary(const std::string& out_dir, const learner::TrainingResult& result,
                  OutputFormat format) {
  const v1::EvaluationLog& log = result.log;
  if (format == OutputFormat::kJson) {
    std::cout << ProtoToJson(log) << std::endl;
    return;
  }
  std::cout << "run           " << out_dir << "\n"
            << "steps         " << result.state.timesteps << " (" << result.state.rollouts
            << " updates)\n";
  if (log.evaluations_size() == 0) return;
  const v1::Evaluation& last = log.evaluations(log.evaluations_size() - 1);
  std::cout << absl::StrFormat(
      "last          avg_combined %.1f at step %d (id %.1f, ood_low %.1f, ood_high %.1f)\n",
      log.last(), last.step(), last.id().mean(), last.ood_low().mean(), last.ood_high().mean());
  if (log.best_anytime_index() >= 0) {
    std::cout << absl::StrFormat("best-anytime  avg_combined %.1f at step %d\n",
                                 log.best_anytime(),
                                 log.evaluations(log.best_anytime_index()).step());
  }
  std::cout << "evaluations   " << run::EvaluationCsvPath(out_dir) << std::endl;
}

int RunTrain(const TrainFlags& flags, const GlobalFlags& global) {
  absl::StatusOr<run::RunRequest> request = CheckRunRequest(flags, global);
  if (!request.ok()) return FailCommand(request.status());
  learner::RestartWithBestBlasKernels(
      [](absl::string_view note) { std::cerr << "dcs: " << note << std::endl; });
  if (!flags.resume) {
    if (absl::Status status = run::CreateRunDirectory(*request); !status.ok()) {
      return FailCommand(status);
    }
  }
  if (absl::Status status = learner::PinTorchThreads(1); !status.ok()) {
    return FailCommand(status);
  }
  const run::RunSpec& spec = request->spec;
  const std::string& out_dir = request->dir;
  std::signal(SIGINT, RequestStop);
  std::signal(SIGTERM, RequestStop);
  ProgressPrinter progress;
  const learner::TrainingOptions options{
      .out_dir = out_dir,
      .resume = flags.resume,
      .keep_checkpoints = flags.keep,
      .on_update =
          [&progress](const learner::TrainingProgress& p) {
            progress.Update(p);
            return !stop_requested;
          }};
  std::optional<learner::TrainingResult> result;
  const absl::Status status =
      env::VisitEnvironment(spec.env, [&]<typename Env>() -> absl::Status {
        DCS_ASSIGN_OR_RETURN(result, learner::Train<Env>(spec, options));
        return absl::OkStatus();
      });
  progress.Finish();
  if (!status.ok()) return FailCommand(status);
  if (!result->complete) {
    std::cerr << "dcs: stopped at step " << result->state.timesteps
              << "; continue with: dcs train --resume --out " << out_dir << std::endl;
    return kExitInterrupted;
  }
  PrintSummary(out_dir, *result, global.output);
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddTrainCommand(CLI::App& dcs, const GlobalFlags& flags) {
  auto train_flags = std::make_shared<TrainFlags>();
  CLI::App* train = dcs.add_subcommand(
      "train", "Train one run of a config in this process (PPO, with the paper's evaluation)");
  train->add_option("--config", train_flags->config,
                    "the run config (YAML; examples in configs/, every key in "
                    "run/run_spec_yaml.h)");
  train->add_option("--out", train_flags->out,
                    "the run's directory: checkpoints, evaluations.csv and .json (default: "
                    "<data-dir>/runs/<config name>-seed<seed>)");
  train->add_option("--seed", train_flags->seed, "the run's seed, instead of the config's")
      ->each([train_flags](const std::string&) { train_flags->seed_given = true; });
  train->add_flag("--resume", train_flags->resume,
                  "continue the run in --out (or the config's default directory) from its "
                  "latest checkpoint");
  train->add_option("--keep", train_flags->keep, "checkpoints to keep")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  return {{train, [train_flags, &flags] { return RunTrain(*train_flags, flags); }}};
}

}  // namespace dcs::services::cli
