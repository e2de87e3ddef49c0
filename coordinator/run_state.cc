// Copyright 2026 The DCS Authors.
#include "coordinator/run_state.h"

#include "absl/strings/str_cat.h"

namespace dcs::coordinator {
namespace {

struct Move {
  RunState from;
  RunState to;
};

constexpr Move kMoves[] = {
    {RunState::kQueued, RunState::kRunning},     {RunState::kRunning, RunState::kQueued},
    {RunState::kRunning, RunState::kCompleted},  {RunState::kRunning, RunState::kFailed},
    {RunState::kQueued, RunState::kCancelled},   {RunState::kRunning, RunState::kCancelled},
};

}  // namespace

bool IsTerminal(RunState state) {
  return state == RunState::kCompleted || state == RunState::kFailed ||
         state == RunState::kCancelled;
}

absl::Status CheckTransition(absl::string_view run_id, RunState from, RunState to) {
  for (const Move& move : kMoves) {
    if (move.from == from && move.to == to) return absl::OkStatus();
  }
  return absl::FailedPreconditionError(absl::StrCat("run ", run_id, " is ",
                                                    NameOf(kRunStateNames, from), " and cannot ",
                                                    "become ", NameOf(kRunStateNames, to)));
}

}  // namespace dcs::coordinator
