// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_SEEDED_RUNS_H_
#define DCS_RUN_SEEDED_RUNS_H_

// A run config read and validated once, to be trained with one seed or several (a sweep's
// trial, a study's trial): each seed's run is the one RequestRun makes of
// ConfigWithSeed(text, seed) (run/run_directory.h), byte for byte, but the text is loaded and
// dumped once for every seed (at the first run asked for: a config only checked costs nothing
// more) and the spec is not read again. Thread-compatible.

#include <cstdint>
#include <optional>
#include <string>

#include "run/run_directory.h"
#include "run/run_spec.h"

namespace dcs::run {

class SeededRuns {
 public:
  // The runs of `config_text`, whose spec, as ParseRunSpecYaml reads it, is `spec` (its seed is
  // replaced by each run's).
  SeededRuns(RunSpec spec, std::string config_text);

  // The run config as read, and its text.
  const RunSpec& spec() const { return spec_; }
  const std::string& config_text() const { return config_text_; }

  // The run of `seed`, its directory not yet chosen (empty): the spec with `seed`, the text
  // ConfigWithSeed(config_text(), seed).
  RunRequest Run(uint64_t seed);

 private:
  RunSpec spec_;
  std::string config_text_;
  bool dumped_yet_ = false;
  // The text as ConfigWithSeed dumps it, up to where it adds the seed; none if the text already
  // has a seed (ConfigWithSeed replaces it where it stands) or is not a mapping.
  std::optional<std::string> dumped_;
};

}  // namespace dcs::run

#endif  // DCS_RUN_SEEDED_RUNS_H_
