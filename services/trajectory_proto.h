// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_TRAJECTORY_PROTO_H_
#define DCS_SERVICES_TRAJECTORY_PROTO_H_

// Conversions between the data plane's messages (dcs/v1/trajectory.proto) and the actor
// library's types: slots' rollouts, journals, policy weights. Tensors are little-endian and
// contiguous (x86-64's layout, copied as is); every tensor is checked, dtype, shape against
// its length, before anything is allocated from it. Errors are INVALID_ARGUMENT naming the
// field. Thread-safe (pure functions).

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "actor/policy_network.h"
#include "actor/policy_weights.h"
#include "actor/rollout_collector.h"
#include "actor/slot_rollout.h"
#include "dcs/v1/trajectory.pb.h"

namespace dcs::services {

v1::SlotRollout SlotRolloutToProto(const actor::SlotRollout& rollout);
absl::StatusOr<actor::SlotRollout> SlotRolloutFromProto(const v1::SlotRollout& proto);

v1::SlotJournal JournalToProto(const actor::SlotJournal& journal);
absl::StatusOr<actor::SlotJournal> JournalFromProto(const v1::SlotJournal& proto);

v1::PolicyWeights WeightsToProto(const actor::PolicyWeights& weights);
absl::StatusOr<actor::PolicyWeights> WeightsFromProto(const v1::PolicyWeights& proto);

// The policy network of `bytes`, a serialised PolicyWeights (as it travels: in pieces,
// services/pieces.h). INVALID_ARGUMENT if they do not parse or do not make a network.
absl::StatusOr<actor::PolicyNetwork> PolicyFromBytes(absl::string_view bytes);

}  // namespace dcs::services

#endif  // DCS_SERVICES_TRAJECTORY_PROTO_H_
