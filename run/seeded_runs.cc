// Copyright 2026 The DCS Authors.
#include "run/seeded_runs.h"

#include <yaml-cpp/yaml.h>

#include <utility>

#include "absl/strings/str_cat.h"

namespace dcs::run {

SeededRuns::SeededRuns(RunSpec spec, std::string config_text)
    : spec_(std::move(spec)), config_text_(std::move(config_text)) {}

RunRequest SeededRuns::Run(uint64_t seed) {
  if (!dumped_yet_) {
    dumped_yet_ = true;
    try {
      const YAML::Node root = YAML::Load(config_text_);
      // ConfigWithSeed adds the seed as the mapping's last key: its dump is this one's and a
      // line.
      if (root.IsMap() && !root["seed"]) dumped_ = YAML::Dump(root);
    } catch (const YAML::Exception&) {
      // Not YAML: ConfigWithSeed keeps the text, each time.
    }
  }
  RunRequest request{.spec = spec_,
                     .config_text = dumped_.has_value()
                                        ? absl::StrCat(*dumped_, "\nseed: ", seed, "\n")
                                        : ConfigWithSeed(config_text_, seed)};
  request.spec.seed = seed;
  return request;
}

}  // namespace dcs::run
