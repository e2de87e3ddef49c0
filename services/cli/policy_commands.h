// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_POLICY_COMMANDS_H_
#define DCS_SERVICES_CLI_POLICY_COMMANDS_H_

// What a researcher does with a trained policy: `dcs eval` (its returns over a grid of one or
// two context features: a generalisation map), `dcs play` (one episode as a video) and
// `dcs export` (its weights for PyTorch). Each reads a run's checkpoint, so each runs in
// `dcs-train` (services/cli/torch_commands.h). A RUN is a run's directory or, if no such
// directory exists, a run on the cluster, downloaded first (LocalRun); `dcs eval` also takes
// SWEEP_ID:CONDITION[:OBSERVE], the completed runs of a sweep's condition, averaged.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "report/gnuplot_figure.h"
#include "services/cli/cli_command.h"

namespace dcs::services::cli {

struct EvalFlags {
  std::vector<std::string> runs;
  std::string checkpoint = "last";  // last, best or a step
  std::vector<std::string> grid;    // FEATURE=LOW:HIGH:N, once or twice
  int episodes = 30;                // per cell
  uint64_t seed = 0;
  std::string out;  // the figure's directory; empty: no figure
  report::FigureFormat format = report::FigureFormat::kPng;
  int threads = 0;  // 0: one per core
  bool yes = false;  // run a grid above the size that asks first
  // Each RUN (a run of the cluster, not a directory) evaluated by the cluster's actors, one job
  // a cell (services/cli/grid_evaluation_client.h), rather than in this process.
  bool on_actors = false;
};

struct PlayFlags {
  std::string run;
  std::string checkpoint = "last";
  std::vector<std::string> context;  // FEATURE=VALUE
  std::string schedule;              // a YAML file: one schedule of the varied feature
  uint64_t seed = 0;
  std::string out;    // .mp4 or .gif
  std::string strip;  // a PNG of a few frames side by side
  int strip_frames = 5;
  bool overlay = true;  // the context, step and return drawn on each frame
};

struct ExportFlags {
  std::string run;
  std::string checkpoint = "last";
  std::string out = "policy.pt";  // the observation layout goes beside it, as .json
};

// A run's directory on this machine: `run` itself if it is a directory; else the run of that id
// on the cluster (`global`'s coordinator), downloaded into a temporary directory that is
// removed with this. NOT_FOUND naming `run` if it is neither.
class LocalRun {
 public:
  static absl::StatusOr<LocalRun> Find(const std::string& run, const GlobalFlags& global);
  ~LocalRun();
  LocalRun(LocalRun&& other) noexcept;
  LocalRun& operator=(LocalRun&&) = delete;
  LocalRun(const LocalRun&) = delete;

  const std::string& dir() const { return dir_; }
  // It is a run of the cluster, downloaded (not a directory of this machine).
  bool on_cluster() const { return temporary_; }

 private:
  LocalRun(std::string dir, bool temporary) : dir_(std::move(dir)), temporary_(temporary) {}
  std::string dir_;
  bool temporary_ = false;
};

std::vector<CliCommand> AddPolicyCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_POLICY_COMMANDS_H_
