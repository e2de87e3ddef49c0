// Copyright 2026 The DCS Authors.
#include "learner/run_checkpoint.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/strip.h"
#include "common/atomic_file.h"
#include "common/random.h"
#include "common/round_trip.h"
#include "common/status_macros.h"

namespace dcs::learner {
namespace {

namespace fs = std::filesystem;

constexpr char kLatest[] = "latest";

// Checkpoint names sort as numbers: fixed width.
std::string CheckpointName(int64_t timesteps) { return absl::StrFormat("%012d", timesteps); }

fs::path CheckpointsDir(const std::string& run_dir) { return fs::path(run_dir) / "checkpoints"; }

// Doubles as exact text (YAML's own formatting would round them).
template <typename Values>
void EmitNumbers(YAML::Emitter& out, const Values& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (double value : values) out << RoundTrip(value);
  out << YAML::EndSeq;
}

std::string ToYaml(const RunState& state, uint64_t learner_checksum) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "timesteps" << YAML::Value << state.timesteps;
  out << YAML::Key << "rollouts" << YAML::Value << state.rollouts;
  out << YAML::Key << "next_evaluation" << YAML::Value << state.next_evaluation;
  out << YAML::Key << "learner_checksum" << YAML::Value << absl::StrCat(learner_checksum);
  out << YAML::Key << "recent_returns" << YAML::Value;
  EmitNumbers(out, state.recent_returns);
  out << YAML::Key << "journals" << YAML::Value << YAML::BeginSeq;
  for (const actor::SlotJournal& journal : state.journals) {
    out << YAML::BeginMap;
    out << YAML::Key << "episode" << YAML::Value << journal.episode;
    out << YAML::Key << "reset_step" << YAML::Value << journal.reset_step;
    out << YAML::Key << "episode_return" << YAML::Value << RoundTrip(journal.episode_return);
    out << YAML::Key << "actions" << YAML::Value;
    EmitNumbers(out, journal.actions);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "evaluations" << YAML::Value << YAML::BeginSeq;
  for (const actor::EvaluationResult& evaluation : state.evaluations) {
    out << YAML::BeginMap << YAML::Key << "step" << YAML::Value << evaluation.step;
    out << YAML::Key << "contexts" << YAML::Value << YAML::BeginSeq;
    for (const actor::ContextResult& context : evaluation.contexts) {
      out << YAML::BeginMap;
      out << YAML::Key << "split" << YAML::Value << actor::SplitName(context.context.split);
      out << YAML::Key << "value" << YAML::Value << RoundTrip(context.context.value);
      out << YAML::Key << "seconds" << YAML::Value << RoundTrip(context.seconds);
      out << YAML::Key << "returns" << YAML::Value;
      EmitNumbers(out, context.returns);
      out << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return absl::StrCat(out.c_str(), "\n");
}

actor::Split SplitFromName(const std::string& name) {
  if (name == "ood_low") return actor::Split::kOodLow;
  if (name == "ood_high") return actor::Split::kOodHigh;
  return actor::Split::kId;
}

// Reads one checkpoint directory. DATA_LOSS for anything unreadable or inconsistent.
absl::StatusOr<Checkpoint> ReadCheckpoint(const fs::path& dir) {
  Checkpoint checkpoint{.name = dir.filename().string()};
  DCS_ASSIGN_OR_RETURN(checkpoint.learner, ReadFile(dir / "learner.bin"));
  DCS_ASSIGN_OR_RETURN(const std::string text, ReadFile(dir / "run.yaml"));
  try {
    const YAML::Node root = YAML::Load(text);
    RunState& state = checkpoint.state;
    state.timesteps = root["timesteps"].as<int64_t>();
    state.rollouts = root["rollouts"].as<int64_t>();
    state.next_evaluation = root["next_evaluation"].as<int64_t>();
    uint64_t checksum = 0;
    if (!absl::SimpleAtoi(root["learner_checksum"].as<std::string>(), &checksum) ||
        checksum != Fnv1a64(checkpoint.learner)) {
      return absl::DataLossError(absl::StrCat(dir.string(), ": learner.bin does not match its ",
                                              "checksum (truncated or corrupt)"));
    }
    state.recent_returns = root["recent_returns"].as<std::vector<double>>();
    for (const YAML::Node& node : root["journals"]) {
      state.journals.push_back({.episode = node["episode"].as<int64_t>(),
                                .reset_step = node["reset_step"].as<int64_t>(),
                                .actions = node["actions"].as<std::vector<float>>(),
                                .episode_return = node["episode_return"].as<double>()});
    }
    for (const YAML::Node& node : root["evaluations"]) {
      actor::EvaluationResult evaluation{.step = node["step"].as<int64_t>()};
      for (const YAML::Node& context : node["contexts"]) {
        evaluation.contexts.push_back(
            {.context = {.split = SplitFromName(context["split"].as<std::string>()),
                         .value = context["value"].as<double>()},
             .returns = context["returns"].as<std::vector<double>>(),
             .seconds = context["seconds"].as<double>()});
      }
      actor::Summarize(evaluation);
      state.evaluations.push_back(std::move(evaluation));
    }
  } catch (const YAML::Exception& e) {
    return absl::DataLossError(absl::StrCat(dir.string(), "/run.yaml is unreadable: ", e.what()));
  }
  return checkpoint;
}

}  // namespace

absl::Status WriteCheckpoint(const std::string& run_dir, const RunState& state,
                             const std::string& learner, int keep) {
  const fs::path root = CheckpointsDir(run_dir);
  const std::string name = CheckpointName(state.timesteps);
  std::error_code error;
  fs::create_directories(root / name, error);
  if (error) {
    return absl::PermissionDeniedError(
        absl::StrCat("cannot create ", (root / name).string(), ": ", error.message()));
  }
  DCS_RETURN_IF_ERROR(WriteFileAtomically(root / name / "learner.bin", learner));
  DCS_RETURN_IF_ERROR(
      WriteFileAtomically(root / name / "run.yaml", ToYaml(state, Fnv1a64(learner))));
  // The pointer last: until it moves, the previous checkpoint is the one a resume reads.
  DCS_RETURN_IF_ERROR(WriteFileAtomically(root / kLatest, name + "\n"));

  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(root, error)) {
    if (entry.is_directory()) names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  for (size_t i = 0; i + keep < names.size(); ++i) fs::remove_all(root / names[i], error);
  return absl::OkStatus();
}

absl::StatusOr<Checkpoint> ReadLatestCheckpoint(const std::string& run_dir) {
  const fs::path root = CheckpointsDir(run_dir);
  absl::StatusOr<std::string> latest = ReadFile(root / kLatest);
  if (!latest.ok()) {
    return absl::NotFoundError(absl::StrCat("no checkpoint in ", root.string()));
  }
  const std::string newest(absl::StripAsciiWhitespace(*latest));
  // The newest first, then older ones that `latest` does not name (a crash after writing a
  // checkpoint but before moving the pointer leaves a newer, complete one).
  std::vector<std::string> names;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(root, error)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && name <= newest) names.push_back(name);
  }
  std::sort(names.rbegin(), names.rend());
  absl::Status last_error = absl::DataLossError(absl::StrCat("no readable checkpoint in ",
                                                             root.string()));
  for (const std::string& name : names) {
    absl::StatusOr<Checkpoint> checkpoint = ReadCheckpoint(root / name);
    if (checkpoint.ok()) return checkpoint;
    last_error = checkpoint.status();
  }
  return absl::DataLossError(last_error.message());
}

}  // namespace dcs::learner
