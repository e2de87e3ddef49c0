// Copyright 2026 The DCS Authors.
//
// `dcs play`: one episode of a trained policy (actor/episode_player.h), recorded by ffmpeg
// (services/cli/episode_video.h) with the shown context features, the step and the return
// drawn on every frame.

#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "actor/episode_player.h"
#include "actor/policy_network.h"
#include "common/atomic_file.h"
#include "common/random.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "env/env_registry.h"
#include "env/schedule_config.h"
#include "learner/trained_policy.h"
#include "run/schedule_yaml.h"
#include "services/cli/context_flags.h"
#include "services/cli/episode_video.h"
#include "services/cli/torch_commands.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

// The schedule of --schedule FILE (one schedule config, as a run config's `schedule`) for the
// run's varied feature, bounded to its training range, seeded from the play's seed.
absl::StatusOr<env::FeatureSchedule> ScheduleFromFile(const std::string& path,
                                                      const run::RunSpec& spec, int feature,
                                                      uint64_t seed) {
  absl::StatusOr<std::string> text = ReadFile(path);
  if (!text.ok()) return Annotate(text.status(), "--schedule");
  DCS_ASSIGN_OR_RETURN(const std::vector<env::ScheduleConfig> configs,
                       run::ParseScheduleConfigsYaml(*text, path));
  if (configs.size() != 1) {
    return absl::InvalidArgumentError(absl::StrCat(
        path, ": an episode plays one schedule, the file holds ", configs.size()));
  }
  absl::StatusOr<env::ScheduleSpec> parsed = env::ParseScheduleSpec(
      configs[0], spec.range_lo, spec.range_hi,
      StreamSeed(seed, "schedule", {0}).GenerateState32(1)[0]);
  if (!parsed.ok()) return Annotate(parsed.status(), path);
  return env::FeatureSchedule{
      .feature = feature,
      .stages = {{.steps = std::numeric_limits<int64_t>::max(), .spec = *std::move(parsed)}}};
}

// The features a frame shows: the run's varied feature, then those --context sets (`assigned`,
// already checked against Env's features).
template <typename Env>
std::vector<int> ShownFeatures(int varied, const std::map<std::string, double>& assigned) {
  std::vector<int> shown = {varied};
  for (const auto& [name, value] : assigned) {
    const int index = *Env::Features().IndexOf(name);
    if (index != varied) shown.push_back(index);
  }
  return shown;
}

// A frame's overlay: "length 0.55" for each shown feature, then the step and the return.
template <typename Env>
std::string OverlayText(const actor::PlayedFrame& frame, const std::vector<int>& shown) {
  std::vector<std::string> features;
  for (int index : shown) {
    features.push_back(absl::StrFormat("%s %.4g", Env::Features().feature(index).name,
                                       frame.features[index]));
  }
  return absl::StrFormat("%s\nstep %d  return %.2f", absl::StrJoin(features, "  "), frame.step,
                         frame.episode_return);
}

template <typename Env>
absl::Status PlayWith(const PlayFlags& flags, const learner::TrainedPolicy& trained) {
  // A demonstration: the run's context (its varied feature at the middle of the training
  // range), no pool, the schedule of --schedule if any.
  env::DynamicContextOptions options = trained.plan.slot;
  options.pools.clear();
  options.schedules.clear();
  DCS_ASSIGN_OR_RETURN(const auto assigned, ParseAssignments(flags.context, "--context"));
  DCS_ASSIGN_OR_RETURN(options.context,
                       ContextWithAssignments<Env>(options.context, assigned, "--context"));
  if (!flags.schedule.empty()) {
    DCS_ASSIGN_OR_RETURN(env::FeatureSchedule schedule,
                         ScheduleFromFile(flags.schedule, trained.run.spec, trained.plan.feature,
                                          flags.seed));
    options.schedules.push_back(std::move(schedule));
  }
  options.run_seed = flags.seed;
  options.slot = 0;
  const std::vector<int> shown = ShownFeatures<Env>(trained.plan.feature, assigned);

  DCS_ASSIGN_OR_RETURN(actor::PolicyNetwork policy,
                       actor::PolicyNetwork::Create(trained.learner->ActorWeights()));
  DCS_ASSIGN_OR_RETURN(EpisodeVideo video,
                       EpisodeVideo::Start({.video = flags.out,
                                            .strip = flags.strip,
                                            .strip_frames = flags.strip_frames,
                                            .width = Env::kRenderWidth,
                                            .height = Env::kRenderHeight,
                                            .fps = Env::kRenderFps,
                                            .overlay = flags.overlay}));
  DCS_ASSIGN_OR_RETURN(const actor::PlayedEpisode episode,
                       actor::PlayEpisode<Env>(policy, options, [&](const actor::PlayedFrame& f) {
                         return video.AddFrame(f.scene->pixels(), OverlayText<Env>(f, shown));
                       }));
  DCS_RETURN_IF_ERROR(video.Finish());
  std::vector<std::string> written;
  for (const std::string& path : {flags.out, flags.strip}) {
    if (!path.empty()) written.push_back(path);
  }
  std::cout << "wrote " << absl::StrJoin(written, " and ") << ": return "
            << absl::StrFormat("%.2f", episode.episode_return) << " in " << episode.steps
            << " steps (" << episode.steps + 1 << " frames)" << std::endl;
  return absl::OkStatus();
}

absl::Status Play(const PlayFlags& flags, const GlobalFlags& global) {
  DCS_ASSIGN_OR_RETURN(const LocalRun local, LocalRun::Find(flags.run, global));
  DCS_ASSIGN_OR_RETURN(const learner::TrainedPolicy trained,
                       learner::LoadTrainedPolicy(local.dir(), flags.checkpoint));
  return env::VisitEnvironment(trained.run.spec.env, [&]<typename Env>() {
    return PlayWith<Env>(flags, trained);
  });
}

}  // namespace

int PlayInProcess(const PlayFlags& flags, const GlobalFlags& global) {
  const absl::Status status = Play(flags, global);
  return status.ok() ? kExitOk : FailCommand(status);
}

}  // namespace dcs::services::cli
