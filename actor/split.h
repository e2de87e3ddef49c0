// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_SPLIT_H_
#define DCS_ACTOR_SPLIT_H_

// The evaluation protocol's splits of evaluation contexts (docs/reference.md, "Evaluation
// protocol"): inside the training range (ID), below it (OOD-low) and above it (OOD-high).
// Thread-safe (constants).

#include <iterator>

#include "common/enum_names.h"

namespace dcs::actor {

enum class Split { kId, kOodLow, kOodHigh };
inline constexpr int kNumSplits = 3;

// As configs (`evaluation.contexts.ood_low`), evaluation logs and checkpoints spell them.
inline constexpr EnumName<Split> kSplitNames[] = {
    {Split::kId, "id"}, {Split::kOodLow, "ood_low"}, {Split::kOodHigh, "ood_high"}};
static_assert(InEnumOrder(kSplitNames) && std::size(kSplitNames) == kNumSplits);

}  // namespace dcs::actor

#endif  // DCS_ACTOR_SPLIT_H_
