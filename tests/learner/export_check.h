// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_LEARNER_EXPORT_CHECK_H_
#define DCS_TESTS_LEARNER_EXPORT_CHECK_H_

// An exported policy (`dcs export`) checked in PyTorch against DCS: check_export.py (beside
// this file) loads the state dict strictly into plain torch modules with Stable-Baselines3's
// layout, built from the layout JSON beside it, and compares on random observations with DCS's
// deterministic actions (actor::PolicyNetwork, what DCS acts with) and values (the learner's
// forward pass). Thread-compatible.

#include <cstdint>
#include <string>
#include <vector>

#include "common/random.h"
#include "learner/trained_policy.h"

namespace dcs::learner {

// `count` random policy inputs of `spec`: flat inputs in [-2, 2] (normalised context values lie
// in [-5, 5], the environments' states mostly within a few units) and random images.
struct Observations {
  std::vector<float> inputs;
  std::vector<uint8_t> images;
};
Observations RandomObservations(const run::PolicySpec& spec, int count, Random& random);

struct ExportCheck {
  int exit_code = -1;  // check_export.py's: 0 if PyTorch agrees with DCS
  std::string output;
};

// check_export.py on the state dict at `policy_path` (its layout beside it), the policy
// exported from `trained`, with 1,000 observations and `trained`'s outputs on them written
// into `dir`. Runs Debian's /usr/bin/python3, where python3-torch installs.
ExportCheck CheckExport(const TrainedPolicy& trained, const std::string& policy_path,
                        const std::string& dir);

}  // namespace dcs::learner

#endif  // DCS_TESTS_LEARNER_EXPORT_CHECK_H_
