// Copyright 2026 The DCS Authors.
#include "services/train_commands.h"

#include <unistd.h>
#include <google/protobuf/util/json_util.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "coordinator/iqm.h"
#include "dcs/proto_json.h"
#include "dcs/v1/evaluation.pb.h"
#include "env/env_registry.h"
#include "learner/run_spec_yaml.h"
#include "learner/torch_runtime.h"
#include "learner/training_run.h"
#include "services/exit_codes.h"
#include "services/text_table.h"

namespace dcs::services {
namespace {

namespace fs = std::filesystem;

constexpr char kStoredConfig[] = "config.yaml";
constexpr int kBootstrapRepetitions = 10'000;

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

// The run's config as stored in its output directory: the file's YAML with `seed` set when
// --seed overrides it (comments are not kept).
absl::StatusOr<std::string> EffectiveConfig(const std::string& path, const TrainFlags& flags) {
  absl::StatusOr<std::string> text = ReadFile(path);
  if (!text.ok()) return absl::NotFoundError(absl::StrCat("cannot read the run config ", path));
  if (!flags.seed_given) return *text;
  try {
    YAML::Node root = YAML::Load(*text);
    if (!root.IsMap()) return *text;  // ParseRunSpecYaml reports it
    root["seed"] = flags.seed;
    return absl::StrCat(YAML::Dump(root), "\n");
  } catch (const YAML::Exception&) {
    return *text;  // ParseRunSpecYaml reports it, with its line
  }
}

// When OpenBLAS fell back to its generic kernels on a CPU it does not recognise
// (learner::BetterBlasCore), runs this program again, the same way, with OPENBLAS_CORETYPE
// naming the right core: OpenBLAS reads it once, when the program loads, so it cannot be set
// later. Returns if there is nothing to do, or if the restart fails (training then runs on the
// generic kernels, only slower).
void RestartWithBetterBlasCore() {
  const std::optional<std::string> core = learner::BetterBlasCore();
  if (!core.has_value()) return;
  absl::StatusOr<std::string> command_line = ReadFile("/proc/self/cmdline");
  if (!command_line.ok()) return;
  std::vector<std::string> words = absl::StrSplit(*command_line, '\0', absl::SkipEmpty());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  std::cerr << "dcs: OpenBLAS does not recognise this CPU and chose its generic kernels; "
               "restarting with OPENBLAS_CORETYPE="
            << *core << " (set OPENBLAS_CORETYPE to choose)" << std::endl;
  setenv("OPENBLAS_CORETYPE", core->c_str(), /*overwrite=*/1);
  execv("/proc/self/exe", argv.data());
  std::cerr << "dcs: cannot restart (" << std::strerror(errno) << "); training on the generic "
            << "kernels" << std::endl;
}

// Where the run's files go: --out, else <data-dir>/runs/<config name>-seed<seed>.
std::string OutputDirectory(const TrainFlags& flags, const GlobalFlags& global, uint64_t seed) {
  if (!flags.out.empty()) return flags.out;
  return (fs::path(global.data_dir) / "runs" /
          absl::StrCat(fs::path(flags.config).stem().string(), "-seed", seed))
      .string();
}

// A run as the command line asks for it: checked, not started.
struct RunRequest {
  learner::RunSpec spec;
  std::string config_text;  // as stored in the run's directory
  std::string out_dir;
};

// Reads and checks the config and the run's directory, changing nothing: a new run needs a
// directory without one; a resumed run needs its stored config, equal to --config if that is
// given too.
absl::StatusOr<RunRequest> CheckRunRequest(const TrainFlags& flags, const GlobalFlags& global) {
  RunRequest request;
  if (flags.resume && flags.config.empty()) {
    if (flags.out.empty()) {
      return absl::InvalidArgumentError("--resume needs --out (the run's directory) or --config");
    }
    request.out_dir = flags.out;
    const std::string stored = (fs::path(request.out_dir) / kStoredConfig).string();
    absl::StatusOr<std::string> text = ReadFile(stored);
    if (!text.ok()) return absl::NotFoundError(absl::StrCat("no run to resume: ", stored));
    request.config_text = *std::move(text);
    DCS_ASSIGN_OR_RETURN(request.spec, learner::ParseRunSpecYaml(request.config_text, stored));
    return request;
  }
  if (flags.config.empty()) return absl::InvalidArgumentError("--config is required");
  DCS_ASSIGN_OR_RETURN(request.config_text, EffectiveConfig(flags.config, flags));
  DCS_ASSIGN_OR_RETURN(request.spec, learner::ParseRunSpecYaml(request.config_text, flags.config));
  request.out_dir = OutputDirectory(flags, global, request.spec.seed);
  const fs::path stored = fs::path(request.out_dir) / kStoredConfig;
  if (flags.resume) {
    absl::StatusOr<std::string> previous = ReadFile(stored.string());
    if (!previous.ok()) {
      return absl::NotFoundError(absl::StrCat("no run to resume in ", request.out_dir));
    }
    if (*previous != request.config_text) {
      return absl::FailedPreconditionError(absl::StrCat(
          request.out_dir, " holds a run of another config (", stored.string(), " differs from ",
          flags.config, flags.seed_given ? " with --seed" : "", ")"));
    }
  } else if (fs::exists(stored)) {
    return absl::FailedPreconditionError(
        absl::StrCat(request.out_dir, " already holds a run: pass --resume to continue it, or "
                                      "--out for a new directory"));
  }
  return request;
}

// Creates a new run's directory, holding its config.
absl::Status CreateRunDirectory(const RunRequest& request) {
  std::error_code error;
  fs::create_directories(request.out_dir, error);
  if (error) {
    return absl::PermissionDeniedError(
        absl::StrCat("cannot create ", request.out_dir, ": ", error.message()));
  }
  return WriteFileAtomically((fs::path(request.out_dir) / kStoredConfig).string(),
                             request.config_text);
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
  std::cout << "evaluations   " << (fs::path(out_dir) / "evaluations.csv").string() << std::endl;
}

int RunTrain(const TrainFlags& flags, const GlobalFlags& global) {
  absl::StatusOr<RunRequest> request = CheckRunRequest(flags, global);
  if (!request.ok()) return FailCommand(request.status());
  RestartWithBetterBlasCore();
  if (!flags.resume) {
    if (absl::Status status = CreateRunDirectory(*request); !status.ok()) {
      return FailCommand(status);
    }
  }
  if (absl::Status status = learner::PinTorchThreads(1); !status.ok()) {
    return FailCommand(status);
  }
  const learner::RunSpec& spec = request->spec;
  const std::string& out_dir = request->out_dir;
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

// The scores of the finished run in `dir`. NOT_FOUND without an evaluation log, DATA_LOSS for
// an unreadable one, FAILED_PRECONDITION for a run that has not finished.
absl::StatusOr<v1::RunScore> ReadRunScore(const std::string& dir) {
  const std::string path = (fs::path(dir) / "evaluations.json").string();
  absl::StatusOr<std::string> json = ReadFile(path);
  if (!json.ok()) return absl::NotFoundError(absl::StrCat("no run in ", dir, ": ", path));
  v1::EvaluationLog log;
  if (!google::protobuf::util::JsonStringToMessage(*json, &log).ok()) {
    return absl::DataLossError(absl::StrCat(path, " is not an evaluation log"));
  }
  if (!log.complete() || log.evaluations_size() == 0) {
    return absl::FailedPreconditionError(absl::StrCat(
        dir, ": the run has not finished (continue it with dcs train --resume --out ", dir, ")"));
  }
  v1::RunScore score;
  score.set_run(dir);
  score.set_seed(log.seed());
  score.set_steps(log.evaluations(log.evaluations_size() - 1).step());
  score.set_last(log.last());
  score.set_best_anytime(log.best_anytime());
  return score;
}

absl::StatusOr<v1::ScoreSummary> SummarizeScore(const std::vector<double>& values) {
  DCS_ASSIGN_OR_RETURN(const coordinator::IqmSummary iqm, coordinator::SummarizeIqm(values));
  DCS_ASSIGN_OR_RETURN(
      const coordinator::ConfidenceInterval interval,
      coordinator::BootstrapIqmInterval({values}, 0.95, kBootstrapRepetitions, /*seed=*/0));
  v1::ScoreSummary summary;
  summary.set_iqm(iqm.iqm);
  summary.set_q1(iqm.q1);
  summary.set_q3(iqm.q3);
  summary.set_ci_low(interval.lo);
  summary.set_ci_high(interval.hi);
  return summary;
}

absl::StatusOr<v1::RunsSummary> SummarizeRuns(const std::vector<std::string>& dirs) {
  v1::RunsSummary summary;
  std::vector<double> last;
  std::vector<double> best;
  for (const std::string& dir : dirs) {
    DCS_ASSIGN_OR_RETURN(*summary.add_runs(), ReadRunScore(dir));
    last.push_back(summary.runs().rbegin()->last());
    best.push_back(summary.runs().rbegin()->best_anytime());
  }
  DCS_ASSIGN_OR_RETURN(*summary.mutable_last(), SummarizeScore(last));
  DCS_ASSIGN_OR_RETURN(*summary.mutable_best_anytime(), SummarizeScore(best));
  return summary;
}

std::string FormatScoreSummary(const v1::ScoreSummary& score) {
  return absl::StrFormat("%.1f [%.1f, %.1f]  (95%% CI of the IQM [%.1f, %.1f])", score.iqm(),
                         score.q1(), score.q3(), score.ci_low(), score.ci_high());
}

int RunSummarize(const std::vector<std::string>& dirs, const GlobalFlags& global) {
  absl::StatusOr<v1::RunsSummary> summary = SummarizeRuns(dirs);
  if (!summary.ok()) return FailCommand(summary.status());
  if (global.output == OutputFormat::kJson) {
    std::cout << ProtoToJson(*summary) << std::endl;
    return kExitOk;
  }
  std::vector<std::vector<std::string>> rows = {{"RUN", "SEED", "STEPS", "LAST", "BEST-ANYTIME"}};
  for (const v1::RunScore& run : summary->runs()) {
    rows.push_back({run.run(), absl::StrCat(run.seed()), absl::StrCat(run.steps()),
                    absl::StrFormat("%.1f", run.last()),
                    absl::StrFormat("%.1f", run.best_anytime())});
  }
  std::cout << RenderTable(rows) << "\n"
            << "avg_combined IQM [Q1, Q3] over " << summary->runs_size() << " runs\n"
            << "  last          " << FormatScoreSummary(summary->last()) << "\n"
            << "  best-anytime  " << FormatScoreSummary(summary->best_anytime()) << std::endl;
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddTrainCommands(CLI::App& dcs, const GlobalFlags& flags) {
  auto train_flags = std::make_shared<TrainFlags>();
  CLI::App* train = dcs.add_subcommand(
      "train", "Train one run of a config in this process (PPO, with the paper's evaluation)");
  train->add_option("--config", train_flags->config,
                    "the run config (YAML; examples in configs/, every key in "
                    "learner/run_spec_yaml.h)");
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

  auto run_dirs = std::make_shared<std::vector<std::string>>();
  CLI::App* summarize = dcs.add_subcommand(
      "summarize", "Scores of finished runs (one condition, several seeds) and their IQM [Q1, Q3]");
  summarize->add_option("runs", *run_dirs, "the runs' directories (as dcs train --out)")
      ->required();
  return {{train, [train_flags, &flags] { return RunTrain(*train_flags, flags); }},
          {summarize, [run_dirs, &flags] { return RunSummarize(*run_dirs, flags); }}};
}

}  // namespace dcs::services
