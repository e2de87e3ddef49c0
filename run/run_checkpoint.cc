// Copyright 2026 The DCS Authors.
#include "run/run_checkpoint.h"

#include <openssl/sha.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <optional>
#include <tuple>

#include "absl/algorithm/container.h"
#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/strip.h"
#include "common/atomic_file.h"
#include "common/enum_names.h"
#include "common/round_trip.h"
#include "common/status_macros.h"

namespace dcs::run {
namespace {

namespace fs = std::filesystem;

constexpr char kLatest[] = "latest";
constexpr char kManifest[] = "MANIFEST";
// The files of a checkpoint besides its manifest, in the order they are written.
constexpr const char* kFiles[] = {"learner.bin", "run.yaml"};

fs::path CheckpointsDir(const std::string& run_dir) { return fs::path(run_dir) / "checkpoints"; }

// A double as exact text (YAML's own formatting would round it), in YAML's spelling when it is
// not finite: the decoder reads back whatever the encoder writes, even a return that overflowed.
std::string YamlNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  return RoundTrip(value);
}

template <typename Values>
void EmitNumbers(YAML::Emitter& out, const Values& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (double value : values) out << YamlNumber(value);
  out << YAML::EndSeq;
}

// A bitset as base64 of its words' little-endian bytes, and back (nullopt unless it decodes to
// `words` words).
std::string EncodeBits(const std::vector<uint64_t>& bits) {
  std::string bytes;
  for (uint64_t word : bits) {
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<char>((word >> (8 * i)) & 0xff));
  }
  return absl::Base64Escape(bytes);
}

std::optional<std::vector<uint64_t>> DecodeBits(const std::string& text, size_t words) {
  std::string bytes;
  if (!absl::Base64Unescape(text, &bytes) || bytes.size() != 8 * words) return std::nullopt;
  std::vector<uint64_t> bits(words);
  for (size_t i = 0; i < bytes.size(); ++i) {
    bits[i / 8] |= uint64_t{static_cast<unsigned char>(bytes[i])} << (8 * (i % 8));
  }
  return bits;
}

void EmitCoverage(YAML::Emitter& out, const ProjectionCounts& counts) {
  out << YAML::BeginMap;
  out << YAML::Key << "projection" << YAML::Value << counts.projection;
  out << YAML::Key << "cells" << YAML::Value << counts.cells;
  out << YAML::Key << "window" << YAML::Value << counts.window;
  out << YAML::Key << "window_new" << YAML::Value << counts.window_new;
  out << YAML::Key << "seen" << YAML::Value << EncodeBits(counts.seen);
  out << YAML::Key << "window_seen" << YAML::Value << EncodeBits(counts.window_seen);
  out << YAML::Key << "closed" << YAML::Value << YAML::BeginSeq;
  for (const CoverageWindow& w : counts.closed) {
    out << YAML::Flow << YAML::BeginSeq << w.start_step << w.end_step << w.visited << w.new_cells
        << YAML::EndSeq;
  }
  out << YAML::EndSeq << YAML::EndMap;
}

// REQUIRES: called inside DecodeRunState's try (yaml-cpp throws on a missing or mistyped key).
absl::StatusOr<ProjectionCounts> DecodeCoverage(const YAML::Node& node,
                                                const std::string& source) {
  ProjectionCounts counts{.projection = node["projection"].as<std::string>(),
                          .cells = node["cells"].as<int64_t>(),
                          .window = node["window"].as<int64_t>(),
                          .window_new = node["window_new"].as<int64_t>()};
  const size_t words = counts.cells > 0 ? BitsetWords(counts.cells) : 0;
  std::optional<std::vector<uint64_t>> seen = DecodeBits(node["seen"].as<std::string>(), words);
  std::optional<std::vector<uint64_t>> window_seen =
      DecodeBits(node["window_seen"].as<std::string>(), words);
  if (words == 0 || !seen.has_value() || !window_seen.has_value()) {
    return absl::DataLossError(absl::StrCat(source, ": the coverage of projection '",
                                            counts.projection, "' does not hold its ",
                                            counts.cells, " cells"));
  }
  counts.seen = *std::move(seen);
  counts.window_seen = *std::move(window_seen);
  for (const YAML::Node& w : node["closed"]) {
    const std::vector<int64_t> values = w.as<std::vector<int64_t>>();
    if (values.size() != 4) {
      return absl::DataLossError(absl::StrCat(source, ": a coverage window of projection '",
                                              counts.projection, "' is not 4 numbers"));
    }
    counts.closed.push_back({.start_step = values[0],
                             .end_step = values[1],
                             .visited = values[2],
                             .new_cells = values[3]});
  }
  return counts;
}

// Reads one checkpoint directory. DATA_LOSS for a file that is missing, does not match the
// manifest, or does not parse.
absl::StatusOr<Checkpoint> ReadCheckpointDir(const fs::path& dir) {
  DCS_ASSIGN_OR_RETURN(const std::string manifest, ReadFile(dir / kManifest));
  std::map<std::string, std::string> contents;
  for (const char* file : kFiles) {
    DCS_ASSIGN_OR_RETURN(contents[file], ReadFile(dir / file));
    if (!absl::StrContains(manifest, absl::StrCat(Sha256Hex(contents[file]), "  ", file, "\n"))) {
      return absl::DataLossError(absl::StrCat((dir / file).string(),
                                              " does not match the checkpoint's MANIFEST ",
                                              "(truncated or corrupt)"));
    }
  }
  DCS_ASSIGN_OR_RETURN(RunState state,
                       DecodeRunState(contents["run.yaml"], (dir / "run.yaml").string()));
  return Checkpoint{.name = dir.filename().string(),
                    .state = std::move(state),
                    .learner = contents["learner.bin"]};
}

}  // namespace

std::string CheckpointName(int64_t timesteps) { return absl::StrFormat("%012d", timesteps); }

std::string Sha256Hex(absl::string_view bytes) {
  unsigned char digest[SHA256_DIGEST_LENGTH];
  SHA256(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), digest);
  std::string hex;
  for (unsigned char byte : digest) absl::StrAppendFormat(&hex, "%02x", byte);
  return hex;
}

std::string EncodeRunState(const RunState& state) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "timesteps" << YAML::Value << state.timesteps;
  out << YAML::Key << "rollouts" << YAML::Value << state.rollouts;
  out << YAML::Key << "recent_returns" << YAML::Value;
  EmitNumbers(out, state.recent_returns);
  out << YAML::Key << "recent_lengths" << YAML::Value << YAML::Flow << state.recent_lengths;
  out << YAML::Key << "journals" << YAML::Value << YAML::BeginSeq;
  for (const actor::SlotJournal& journal : state.journals) {
    out << YAML::BeginMap;
    out << YAML::Key << "episode" << YAML::Value << journal.episode;
    out << YAML::Key << "reset_step" << YAML::Value << journal.reset_step;
    out << YAML::Key << "episode_return" << YAML::Value << YamlNumber(journal.episode_return);
    out << YAML::Key << "actions" << YAML::Value;
    EmitNumbers(out, journal.actions);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "evaluations" << YAML::Value << YAML::BeginSeq;
  for (const actor::EvaluationResult& evaluation : state.evaluations) {
    out << YAML::BeginMap << YAML::Key << "step" << YAML::Value << evaluation.step;
    out << YAML::Key << "updates" << YAML::Value << evaluation.updates;
    out << YAML::Key << "contexts" << YAML::Value << YAML::BeginSeq;
    for (const actor::ContextResult& context : evaluation.contexts) {
      out << YAML::BeginMap;
      out << YAML::Key << "split" << YAML::Value
          << std::string(NameOf(actor::kSplitNames, context.context.split));
      out << YAML::Key << "value" << YAML::Value << YamlNumber(context.context.value);
      out << YAML::Key << "seconds" << YAML::Value << YamlNumber(context.seconds);
      out << YAML::Key << "returns" << YAML::Value;
      EmitNumbers(out, context.returns);
      out << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::EndMap;
  }
  out << YAML::EndSeq;
  if (!state.coverage.empty()) {
    out << YAML::Key << "coverage" << YAML::Value << YAML::BeginSeq;
    for (const ProjectionCounts& counts : state.coverage) EmitCoverage(out, counts);
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  return absl::StrCat(out.c_str(), "\n");
}

absl::StatusOr<RunState> DecodeRunState(const std::string& text, const std::string& source) {
  RunState state;
  try {
    const YAML::Node root = YAML::Load(text);
    state.timesteps = root["timesteps"].as<int64_t>();
    state.rollouts = root["rollouts"].as<int64_t>();
    state.recent_returns = root["recent_returns"].as<std::vector<double>>();
    if (root["recent_lengths"]) {
      state.recent_lengths = root["recent_lengths"].as<std::vector<int64_t>>();
    }
    for (const YAML::Node& node : root["journals"]) {
      state.journals.push_back({.episode = node["episode"].as<int64_t>(),
                                .reset_step = node["reset_step"].as<int64_t>(),
                                .actions = node["actions"].as<std::vector<float>>(),
                                .episode_return = node["episode_return"].as<double>()});
    }
    for (const YAML::Node& node : root["evaluations"]) {
      actor::EvaluationResult evaluation{.step = node["step"].as<int64_t>(),
                                         .updates = node["updates"].as<int64_t>()};
      for (const YAML::Node& context : node["contexts"]) {
        const std::string split_name = context["split"].as<std::string>();
        const std::optional<actor::Split> split = FindByName(actor::kSplitNames, split_name);
        if (!split.has_value()) {
          return absl::DataLossError(absl::StrCat(source, " names an unknown evaluation split '",
                                                  split_name, "'"));
        }
        evaluation.contexts.push_back(
            {.context = {.split = *split, .value = context["value"].as<double>()},
             .returns = context["returns"].as<std::vector<double>>(),
             .seconds = context["seconds"].as<double>()});
      }
      actor::Summarize(evaluation);
      state.evaluations.push_back(std::move(evaluation));
    }
    for (const YAML::Node& node : root["coverage"]) {
      DCS_ASSIGN_OR_RETURN(ProjectionCounts counts, DecodeCoverage(node, source));
      state.coverage.push_back(std::move(counts));
    }
  } catch (const YAML::Exception& e) {
    return absl::DataLossError(absl::StrCat(source, " is unreadable: ", e.what()));
  }
  return state;
}

PackedCheckpoint PackCheckpoint(const Checkpoint& checkpoint) {
  PackedCheckpoint packed{.name = checkpoint.name,
                          .learner = checkpoint.learner,
                          .run_state = EncodeRunState(checkpoint.state)};
  packed.learner_sha256 = Sha256Hex(packed.learner);
  packed.run_state_sha256 = Sha256Hex(packed.run_state);
  return packed;
}

absl::StatusOr<int64_t> CheckPackedCheckpoint(const PackedCheckpoint& packed) {
  int64_t timesteps = -1;
  if (packed.name.size() != CheckpointName(0).size() ||
      !absl::c_all_of(packed.name, absl::ascii_isdigit) ||
      !absl::SimpleAtoi(packed.name, &timesteps)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "\"", packed.name, "\" is not a checkpoint's name (its step, as ", CheckpointName(0),
        " is step 0)"));
  }
  for (const auto& [file, bytes, sent] :
       {std::tuple("learner.bin", &packed.learner, &packed.learner_sha256),
        std::tuple("run.yaml", &packed.run_state, &packed.run_state_sha256)}) {
    const std::string computed = Sha256Hex(*bytes);
    if (computed != *sent) {
      return absl::DataLossError(absl::StrCat(file, " of checkpoint ", packed.name,
                                              " arrived corrupt: its SHA-256 is ", computed,
                                              ", the sender's ", *sent));
    }
  }
  return timesteps;
}

absl::StatusOr<Checkpoint> UnpackCheckpoint(const PackedCheckpoint& packed) {
  DCS_RETURN_IF_ERROR(CheckPackedCheckpoint(packed).status());
  DCS_ASSIGN_OR_RETURN(RunState state,
                       DecodeRunState(packed.run_state,
                                      absl::StrCat("run.yaml of checkpoint ", packed.name)));
  if (packed.name != CheckpointName(state.timesteps)) {
    return absl::InvalidArgumentError(absl::StrCat("checkpoint ", packed.name, " holds step ",
                                                   state.timesteps, "; it must be named ",
                                                   CheckpointName(state.timesteps)));
  }
  return Checkpoint{.name = packed.name, .state = std::move(state), .learner = packed.learner};
}

absl::Status WriteCheckpoint(const std::string& run_dir, const RunState& state,
                             const std::string& learner, int keep) {
  return WritePackedCheckpoint(
      run_dir,
      PackCheckpoint({.name = CheckpointName(state.timesteps), .state = state, .learner = learner}),
      keep);
}

absl::Status WritePackedCheckpoint(const std::string& run_dir, const PackedCheckpoint& packed,
                                   int keep) {
  const fs::path root = CheckpointsDir(run_dir);
  const std::string& name = packed.name;
  std::error_code error;
  fs::create_directories(root / name, error);
  if (error) {
    return absl::PermissionDeniedError(
        absl::StrCat("cannot create ", (root / name).string(), ": ", error.message()));
  }
  // The manifest (sha256sum's format: `sha256sum -c MANIFEST` checks it) after the files it
  // vouches for.
  const std::string* contents[][2] = {{&packed.learner, &packed.learner_sha256},
                                       {&packed.run_state, &packed.run_state_sha256}};
  static_assert(std::size(contents) == std::size(kFiles));
  std::string manifest;
  for (size_t i = 0; i < std::size(kFiles); ++i) {
    DCS_RETURN_IF_ERROR(WriteFileAtomically(root / name / kFiles[i], *contents[i][0]));
    absl::StrAppend(&manifest, *contents[i][1], "  ", kFiles[i], "\n");
  }
  DCS_RETURN_IF_ERROR(WriteFileAtomically(root / name / kManifest, manifest));
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

absl::StatusOr<std::vector<std::string>> CheckpointNames(const std::string& run_dir) {
  const fs::path root = CheckpointsDir(run_dir);
  absl::StatusOr<std::string> latest = ReadFile(root / kLatest);
  if (!latest.ok()) {
    return absl::NotFoundError(absl::StrCat("no checkpoint in ", root.string()));
  }
  const std::string newest(absl::StripAsciiWhitespace(*latest));
  std::vector<std::string> names;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(root, error)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && name <= newest) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

absl::StatusOr<Checkpoint> ReadCheckpoint(const std::string& run_dir, const std::string& name) {
  const fs::path dir = CheckpointsDir(run_dir) / name;
  std::error_code error;
  if (!fs::is_directory(dir, error)) {
    return absl::NotFoundError(absl::StrCat("no checkpoint ", dir.string()));
  }
  return ReadCheckpointDir(dir);
}

absl::StatusOr<Checkpoint> ReadLatestCheckpoint(const std::string& run_dir) {
  DCS_ASSIGN_OR_RETURN(std::vector<std::string> names, CheckpointNames(run_dir));
  // The one `latest` names, then older ones.
  absl::Status last_error = absl::DataLossError(
      absl::StrCat("no readable checkpoint in ", CheckpointsDir(run_dir).string()));
  for (auto name = names.rbegin(); name != names.rend(); ++name) {
    absl::StatusOr<Checkpoint> checkpoint = ReadCheckpoint(run_dir, *name);
    if (checkpoint.ok()) return checkpoint;
    last_error = checkpoint.status();
  }
  return absl::DataLossError(last_error.message());
}

}  // namespace dcs::run
