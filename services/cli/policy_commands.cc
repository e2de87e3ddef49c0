// Copyright 2026 The DCS Authors.
#include "services/cli/policy_commands.h"

#include <stdlib.h>

#include <memory>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "services/cli/cluster_client.h"
#include "services/cli/run_client.h"
#include "services/cli/torch_commands.h"
#include "services/command_line.h"

namespace dcs::services::cli {
namespace fs = std::filesystem;

absl::StatusOr<LocalRun> LocalRun::Find(const std::string& run, const GlobalFlags& global) {
  std::error_code error;
  if (fs::is_directory(run, error)) return LocalRun(run, /*temporary=*/false);
  if (run.find('/') != std::string::npos) {
    return absl::NotFoundError(absl::StrCat("no run directory ", run));
  }
  std::string dir = (fs::temp_directory_path(error) / "dcs-run-XXXXXX").string();
  if (mkdtemp(dir.data()) == nullptr) {
    return absl::PermissionDeniedError(absl::StrCat("cannot create a directory like ", dir,
                                                    " to download run ", run, " into"));
  }
  LocalRun local(std::move(dir), /*temporary=*/true);
  const std::string address = CoordinatorAddress(global);
  if (absl::Status status = DownloadRun(address, run, local.dir(), global.timeout);
      !status.ok()) {
    if (absl::IsNotFound(status)) {
      return absl::NotFoundError(absl::StrCat(
          "no run ", run, ": neither a directory nor a run on the cluster at ", address));
    }
    return absl::Status(status.code(),
                        absl::StrCat(run, " is not a directory; as a run on the cluster: ",
                                     status.message()));
  }
  return local;
}

LocalRun::LocalRun(LocalRun&& other) noexcept
    : dir_(std::move(other.dir_)), temporary_(other.temporary_) {
  other.temporary_ = false;
}

LocalRun::~LocalRun() {
  std::error_code error;
  if (temporary_) fs::remove_all(dir_, error);
}

namespace {

constexpr char kRunHelp[] =
    "a run: its directory (as `dcs train --out` writes it, or `dcs runs get`), or a run "
    "id on the cluster";
constexpr char kCheckpointHelp[] =
    "last, best (of the kept checkpoints, the best on the run's own evaluation protocol), or "
    "the step of a kept checkpoint";

}  // namespace

std::vector<CliCommand> AddPolicyCommands(CLI::App& dcs, const GlobalFlags& global) {
  auto eval_flags = std::make_shared<EvalFlags>();
  CLI::App* eval = dcs.add_subcommand(
      "eval", "Evaluate trained policies over a grid of one or two context features: a table "
              "and a generalisation map");
  eval->add_option("RUN", eval_flags->runs,
                   absl::StrCat(kRunHelp, "; or SWEEP_ID:CONDITION[:OBSERVE], a sweep "
                                          "condition's completed runs, averaged"))
      ->required();
  eval->add_option("--checkpoint", eval_flags->checkpoint, kCheckpointHelp)
      ->capture_default_str();
  eval->add_option("--grid", eval_flags->grid,
                   "FEATURE=LOW:HIGH:N, N values from LOW to HIGH; once (lines) or twice (a "
                   "heatmap)")
      ->required();
  eval->add_option("--episodes", eval_flags->episodes, "deterministic episodes per cell")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  eval->add_option("--seed", eval_flags->seed,
                   "the episodes' seed (cell c's episode i resets as the run's evaluation "
                   "context c would)")
      ->capture_default_str();
  AddOutDirectory(*eval, &eval_flags->out,
                  "a directory for the figure: its data, gnuplot script and image");
  AddChoiceOption(*eval, "--format", &eval_flags->format, ChoicesOf(report::kFigureFormatNames),
                  "the image: svg, png or pdf");
  eval->add_option("--threads", eval_flags->threads, "threads evaluating (default: one a core)")
      ->check(CLI::Range(0, 1024));
  eval->add_flag("--yes", eval_flags->yes, "run a grid however many episodes it makes");
  eval->add_flag("--on-actors", eval_flags->on_actors,
                 "evaluate on the cluster's actors instead of in this process (each RUN a run "
                 "of the cluster; the same returns, bit for bit)");

  auto play_flags = std::make_shared<PlayFlags>();
  CLI::App* play = dcs.add_subcommand(
      "play", "Record one episode of a trained policy as a video (mp4 or gif), with the "
              "context, step and return drawn on each frame");
  play->add_option("RUN", play_flags->run, kRunHelp)->required();
  play->add_option("--checkpoint", play_flags->checkpoint, kCheckpointHelp)
      ->capture_default_str();
  play->add_option("--context", play_flags->context,
                   "a context feature's value, FEATURE=VALUE (repeatable; default: the run's "
                   "context, its varied feature at the middle of the training range), held "
                   "for the whole episode");
  play->add_option("--schedule", play_flags->schedule,
                   "a YAML file of one schedule (as a run config's `schedule`) moving the "
                   "run's varied feature within the episode, in its training range "
                   "(default: none)");
  play->add_option("--seed", play_flags->seed,
                   "the episode's seed (its reset and its schedule's draws)")
      ->capture_default_str();
  AddOutFile(*play, &play_flags->out,
             "the video: NAME.mp4 or NAME.gif, one frame per step and one of the reset, at "
             "the environment's 50 fps (needs Debian's ffmpeg)");
  play->add_option("--strip", play_flags->strip,
                   "a few frames spread over the episode side by side as one PNG, NAME.png, for "
                   "a README or a paper");
  play->add_option("--strip-frames", play_flags->strip_frames, "frames in the strip")
      ->capture_default_str()
      ->check(CLI::Range(2, 12));
  play->add_flag("!--no-overlay", play_flags->overlay,
                 "the scene alone, without the context, step and return");

  auto export_flags = std::make_shared<ExportFlags>();
  CLI::App* export_command = dcs.add_subcommand(
      "export", "Write a trained policy as a PyTorch state dict with Stable-Baselines3's "
                "parameter names, and its observation layout as JSON beside it");
  export_command->add_option("RUN", export_flags->run, kRunHelp)->required();
  export_command->add_option("--checkpoint", export_flags->checkpoint, kCheckpointHelp)
      ->capture_default_str();
  AddOutFile(*export_command, &export_flags->out,
             "the state dict, NAME.pt; the layout goes to NAME.json beside it")
      ->capture_default_str();

  return {
      {eval, [eval_flags, &global] { return EvaluateInProcess(*eval_flags, global); },
       kEveryFormat},
      {play, [play_flags, &global] { return PlayInProcess(*play_flags, global); }},
      {export_command,
       [export_flags, &global] { return ExportInProcess(*export_flags, global); }},
  };
}

}  // namespace dcs::services::cli
