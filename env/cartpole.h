// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_CARTPOLE_H_
#define DCS_ENV_CARTPOLE_H_

// Gymnasium's CartPole-v1 (1.4.0, gymnasium/envs/classic_control/cartpole.py) with CARL's context
// features (docs/reference.md, "Context features and payloads"): float64 explicit-Euler physics,
// strict termination bounds (|x| > 2.4, |theta| > 12 degrees), reward 1 per step up to and
// including the first terminating step and 0 after it, truncation at 500 steps, and a float32
// observation [x, x_dot, theta, theta_dot].
//
// Context features may change at any time (a schedule moves them mid-episode): a new value
// takes effect at the next physics step, and the derived total mass and pole mass-length are
// recomputed at once (Gymnasium computes them only at construction).
//
// Reset draws x, x_dot, theta, theta_dot in that order from U(initial_state_lower,
// initial_state_upper), which is Gymnasium's draw order: with a numpy-exact generator seeded
// as Gymnasium seeds it, the same seed gives the same initial state. The default bounds are
// CARL's +-0.1 (the paper trained CARL's CartPole); Gymnasium's own are +-0.05.
//
// Thread-compatible; one instance per environment slot.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/status.h"
#include "common/random.h"
#include "env/context_feature.h"
#include "env/raster.h"
#include "env/state_projection.h"
#include "env/step_result.h"

namespace dcs::env {

struct CartPoleState {
  double x = 0;          // cart position, m
  double x_dot = 0;      // cart velocity, m/s
  double theta = 0;      // pole angle from upright, rad
  double theta_dot = 0;  // pole angular velocity, rad/s
};

class CartPole final {
 public:
  // The shape every DCS environment declares (env/dynamic_context_env.h uses it).
  static constexpr absl::string_view kName = "cartpole";
  using Observation = float;
  using ActionElement = int32_t;  // 0 pushes left, 1 pushes right
  static constexpr int kObservationSize = 4;
  static constexpr int kActionSize = 1;
  static constexpr int kNumActions = 2;
  static constexpr int kMaxEpisodeSteps = 500;

  // Feature indices into Features().
  enum Feature : int {
    kGravity,            // m/s^2
    kMassCart,           // kg
    kMassPole,           // kg
    kLength,             // m, HALF the pole length
    kForceMag,           // N
    kTau,                // s per step
    kInitialStateLower,  // reset distribution, every state dimension
    kInitialStateUpper,
    kNumFeatures
  };

  static constexpr double kXThreshold = 2.4;
  static constexpr double kThetaThreshold = 12 * 2 * 3.141592653589793 / 360;

  // CARL's CartPole features, with the paper's sensor bounds for the length (0.05, 2.0) m.
  static const ContextSpace& Features();

  // The coverage diagnostic's projection (docs/reference.md, "Coverage"): "state", the four
  // observation dimensions in 12 bins each over the paper's physically plausible ranges.
  static const std::vector<StateProjection>& CoverageProjections();

  // OK if every value is valid for its feature and initial_state_lower <= initial_state_upper.
  static absl::Status ValidateContext(std::span<const double> values);

  // Starts with the default context and the state (0, 0, 0, 0).
  CartPole();

  double GetFeature(int feature) const { return features_[feature]; }
  // REQUIRES: `value` valid for `feature` (ContextSpace::Validate).
  void SetFeature(int feature, double value);

  // Draws a new initial state and writes its observation.
  void Reset(Random& random, std::span<float, kObservationSize> observation);
  // Starts from `state` (for tests and `dcs env trace`).
  void ResetTo(const CartPoleState& state, std::span<float, kObservationSize> observation);

  // One physics step with action 0 (left) or 1 (right). Stepping on after termination is
  // allowed, as in Gymnasium: the dynamics keep integrating and the reward is 0.
  StepResult Step(std::span<const int32_t, kActionSize> action,
                  std::span<float, kObservationSize> observation);

  const CartPoleState& state() const { return state_; }

  // Draws the scene as Gymnasium's render does: a 600x400 frame, 125 px
  // per metre, the cart in black on its track, the pole in brown and the axle in lilac.
  static constexpr int kRenderWidth = 600;
  static constexpr int kRenderHeight = 400;
  static constexpr int kRenderFps = 50;  // Gymnasium's metadata["render_fps"]
  // REQUIRES: canvas is kRenderWidth x kRenderHeight.
  void Render(Canvas& canvas) const;

 private:
  void WriteObservation(std::span<float, kObservationSize> observation) const;

  std::array<double, kNumFeatures> features_;
  double total_mass_;       // masspole + masscart
  double polemass_length_;  // masspole * length
  CartPoleState state_;
  int elapsed_steps_ = 0;
  bool terminated_before_ = false;  // Gymnasium's steps_beyond_terminated is set
};

}  // namespace dcs::env

#endif  // DCS_ENV_CARTPOLE_H_
