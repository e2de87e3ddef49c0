// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_SCHEDULE_H_
#define DCS_ENV_SCHEDULE_H_

// The state machine that moves one context feature along a ScheduleSpec (env/schedule_spec.h)
// within each episode, and the one factory that builds it.
//
// Protocol, driven by the dynamic-context wrapper (env/dynamic_context_env.h):
//   v = schedule.Reset(initial, {episode, slot});   // at reset: the value to apply
//   v = schedule.Next(k, v);                         // before physics step k + 1, k = 1, 2, ...
// `initial` is the feature's episode-initial value (drawn from the pool); `k` counts the
// scheduled calls of the episode: the first transition of an episode makes none, so call k
// precedes the (k + 1)-th transition (docs/reference.md, "Step timing"). Event times (jumps,
// switches, cycles) compare with k. Every returned value is within [min_value, max_value], except
// that Identity and the first-call skip return the current value unchanged.
//
// Randomness: each Reset starts a fresh generator derived from (spec.seed, episode, slot), so
// an episode's trajectory depends on nothing but those three numbers.
//
// Confined to one thread; one instance per environment slot and feature.

#include <cstdint>
#include <memory>
#include <vector>

#include "env/schedule_spec.h"

namespace dcs::env {

// Which episode of which environment slot a schedule is running.
struct EpisodeId {
  uint64_t episode = 0;  // counts the slot's episodes from 0
  uint64_t slot = 0;
};

class Schedule {
 public:
  virtual ~Schedule() = default;

  // Starts an episode whose feature starts at `initial`; returns the value to apply.
  virtual double Reset(double initial, EpisodeId id) = 0;

  // The value for scheduled call `k` (k >= 1), given the feature's current value.
  virtual double Next(int64_t k, double current) = 0;
};

// Builds the state machine of `spec`. REQUIRES: `spec` valid (as ParseScheduleSpec returns).
std::unique_ptr<Schedule> MakeSchedule(const ScheduleSpec& spec);

// The feature's value during each of an episode's first `transitions` transitions, when nothing
// but `schedule` moves it: the reset value for the first, then Next(k) before transition k + 1.
std::vector<double> ScheduleTrajectory(Schedule& schedule, double initial, EpisodeId id,
                                       int transitions);

}  // namespace dcs::env

#endif  // DCS_ENV_SCHEDULE_H_
