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
    {RunState::kFailed, RunState::kQueued},
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

SweepState SweepStateOf(std::span<const std::pair<RunState, int64_t>> runs_by_state,
                        bool cancelled, bool open) {
  int64_t total = 0;
  auto count = [&](RunState wanted) {
    int64_t n = 0;
    for (const auto& [state, runs] : runs_by_state) n += state == wanted ? runs : 0;
    return n;
  };
  for (const auto& [state, runs] : runs_by_state) total += runs;
  const int64_t queued = count(RunState::kQueued);
  if (queued == total && (total > 0 || open)) return SweepState::kQueued;
  if (open || queued + count(RunState::kRunning) > 0) return SweepState::kRunning;
  if (cancelled) return SweepState::kCancelled;
  return count(RunState::kFailed) > 0 ? SweepState::kFailed : SweepState::kCompleted;
}

}  // namespace dcs::coordinator
