// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_RUN_STATE_H_
#define DCS_COORDINATOR_RUN_STATE_H_

// The life of a run in the coordinator, as one table of states and one of the moves between
// them (every transition goes through one function):
//
//   queued ──▶ running ──▶ completed | failed
//     ▲           │
//     └───────────┘  its learner's lease lapsed: back to the queue, to resume from its last
//                    checkpoint on whichever learner takes it next
//   queued | running ──▶ cancelled
//   failed ──▶ queued     a client retried it (`dcs retry`): it resumes from its last checkpoint
//
// A sweep's state is derived from its runs' (SweepStateOf), never stored.
//
// Thread-safe (constant data, pure functions).

#include <cstdint>
#include <span>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "common/enum_names.h"

namespace dcs::coordinator {

enum class RunState { kQueued, kRunning, kCompleted, kFailed, kCancelled };

inline constexpr EnumName<RunState> kRunStateNames[] = {
    {RunState::kQueued, "queued"},       {RunState::kRunning, "running"},
    {RunState::kCompleted, "completed"}, {RunState::kFailed, "failed"},
    {RunState::kCancelled, "cancelled"}};
static_assert(InEnumOrder(kRunStateNames));

// Completed, failed or cancelled: no worker moves it any more (only a client's retry of a
// failed run does).
bool IsTerminal(RunState state);

// OK if a run may move from `from` to `to`; otherwise FAILED_PRECONDITION naming both (and the
// run `run_id`).
absl::Status CheckTransition(absl::string_view run_id, RunState from, RunState to);

enum class SweepState { kQueued, kRunning, kCompleted, kFailed, kCancelled };

inline constexpr EnumName<SweepState> kSweepStateNames[] = {
    {SweepState::kQueued, "queued"},       {SweepState::kRunning, "running"},
    {SweepState::kCompleted, "completed"}, {SweepState::kFailed, "failed"},
    {SweepState::kCancelled, "cancelled"}};
static_assert(InEnumOrder(kSweepStateNames));

// A sweep of runs counted by state (`runs_by_state`): queued while every run is (or, `open`,
// while it has none); running while any is queued or running, or while it is `open` (a study
// sweep that will add runs); then cancelled if the sweep was (`cancelled`), failed if any run
// failed, else completed.
SweepState SweepStateOf(std::span<const std::pair<RunState, int64_t>> runs_by_state,
                        bool cancelled, bool open);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_RUN_STATE_H_
