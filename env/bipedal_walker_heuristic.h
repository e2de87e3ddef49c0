// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_BIPEDAL_WALKER_HEURISTIC_H_
#define DCS_ENV_BIPEDAL_WALKER_HEURISTIC_H_

// Gymnasium's hand-written BipedalWalker controller (BipedalWalkerHeuristics in
// bipedal_walker.py): a three-phase gait (stand on one leg, put the other down, push off) with PD
// targets on the joints, head stabilisation and vertical damping. It "has no notion of balance" and
// falls often: Gymnasium's mean return is about 102.6 +- 125.1 on normal terrain. The check that a
// walker port walks, and a baseline policy. Drive it as Gymnasium does: reset, take a zero action
// first, then Act on each step's observation (the reset observation is unused). Thread-compatible;
// one instance per episode stream.

#include <array>
#include <span>

namespace dcs::env {

class WalkerHeuristic {
 public:
  // Back to the first phase, leg 0 moving.
  void Reset();

  // The next action, each element in [-1, 1], for `observation` (BipedalWalker's layout).
  std::array<float, 4> Act(std::span<const float, 24> observation);

 private:
  enum Phase { kStayOnOneLeg = 1, kPutOtherDown = 2, kPushOff = 3 };

  Phase phase_ = kStayOnOneLeg;
  int moving_leg_ = 0;
  int supporting_leg_ = 1;
  double supporting_knee_angle_ = 0.1;
};

}  // namespace dcs::env

#endif  // DCS_ENV_BIPEDAL_WALKER_HEURISTIC_H_
