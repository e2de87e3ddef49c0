// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_OBSERVE_MODE_H_
#define DCS_ENV_OBSERVE_MODE_H_

// What a policy is shown of its environment's context (docs/reference.md, "Observation modes and
// normalisation"; env/dynamic_context_env.h): nothing (the paper's "blind"), the episode's initial
// values, or the live values (the paper's "observed"). Thread-safe (constants).

#include "common/enum_names.h"

namespace dcs::env {

enum class ObserveMode { kNone, kInitial, kLive };

// As run configs spell them (`observe: live`).
inline constexpr EnumName<ObserveMode> kObserveModeNames[] = {
    {ObserveMode::kNone, "none"}, {ObserveMode::kInitial, "initial"}, {ObserveMode::kLive, "live"}};
static_assert(InEnumOrder(kObserveModeNames));

}  // namespace dcs::env

#endif  // DCS_ENV_OBSERVE_MODE_H_
