// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_POLICY_EXPORT_H_
#define DCS_LEARNER_POLICY_EXPORT_H_

// A trained policy for PyTorch (`dcs export`; docs/export.md): its weights as a state dict
// under Stable-Baselines3's names (PpoLearner::Sb3StateDict), and the layout of what its
// network takes and gives (dcs.v1.PolicyLayout, proto/dcs/v1/policy_export.proto) as JSON.
// Thread-safe (functions of their arguments; the policy is only read).

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "dcs/v1/policy_export.pb.h"
#include "learner/trained_policy.h"

namespace dcs::learner {

struct ExportedPolicy {
  std::string state_dict;  // the bytes of a file torch.load reads
  v1::PolicyLayout layout;
};

// The export of `trained`. INTERNAL if libtorch fails to write the state dict.
absl::StatusOr<ExportedPolicy> ExportPolicy(const TrainedPolicy& trained);

// The path of the layout beside the state dict at `state_dict_path`: the same stem, .json.
// INVALID_ARGUMENT if `state_dict_path` itself ends in .json (the two would be one file).
absl::StatusOr<std::string> LayoutPathFor(const std::string& state_dict_path);

// Writes `exported`: the state dict to `state_dict_path`, the layout as JSON beside it
// (LayoutPathFor), each atomically (common/atomic_file.h: an error leaves an older file as it
// was). INVALID_ARGUMENT as LayoutPathFor; WriteFileAtomically's errors, naming the file.
absl::Status WriteExportedPolicy(const ExportedPolicy& exported,
                                 const std::string& state_dict_path);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_POLICY_EXPORT_H_
