// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_BIPEDAL_WALKER_H_
#define DCS_ENV_BIPEDAL_WALKER_H_

// Gymnasium's BipedalWalker-v3 (1.4.0, gymnasium/envs/box2d/bipedal_walker.py) on Box2D 2.4.1, with
// CARL's 20 walker context features (docs/reference.md, "Context features and payloads"), the
// reference implementation's COM_X payload and a HARDCORE switch. Observation: 24 float32 values
// (hull angle, angular velocity, velocity, joint angles and speeds, foot contacts, ten lidar
// fractions); action: 4 floats (hip, knee, hip, knee), meant in [-1, 1]: the sign picks the motor
// direction, |a| clipped to 1 scales its torque. Reward: forward progress minus head tilt and
// torque cost, -100 on a fall.
//
// When a feature change takes effect (a schedule may move any feature mid-episode):
// - at the next Step: GRAVITY_X/Y, FRICTION (terrain fixtures and the friction of existing
//   contacts), MOTORS_TORQUE (motor torque and the torque cost), SPEED_HIP/KNEE (motor speeds
//   and the joint-speed scaling), LIDAR_RANGE, FPS (time step and the velocity scaling), and
//   COM_X, PAYLOAD_MASS, PAYLOAD_RADIUS (the payload fixture is destroyed and re-created at
//   the new place, the hull's mass data recomputed; done only when a value changed);
// - at the next Reset: SCALE (hull size, reward and observation scaling), TERRAIN_*, LEG_*,
//   INITIAL_RANDOM, VIEWPORT_W/H (observation scaling, view), HARDCORE (terrain and the time
//   limit). These shape the world built at reset, so a change mid-episode is only recorded.
// No feature value within its bounds can corrupt a running world.
//
// Reset builds the world (terrain, clouds, walker), takes Gymnasium's internal zero-action step
// and returns its observation; the payload is then attached, as the reference's wrapper does
// after the base reset, so it acts from the first agent step. With a numpy-exact Random seeded
// as Gymnasium seeds it, a seed gives Gymnasium's terrain and initial push (Box2D 2.4 trajectories
// differ numerically from Gymnasium's 2.3 ones).
//
// Deviations from the sources, all deliberate: TERRAIN_HEIGHT defaults to Gymnasium's 400/30/4
// (CARL says 600/30/4 = 5; the base environment is BipedalWalker-v3 exactly); parameters are
// per instance (CARL writes module globals); the payload defaults to the paper's 2 kg and 0.5 m
// and keeps the reference's default collision filter (WalkerPayload: a payload touching the
// terrain or a lower leg is a hull contact, so a fall, and lidar rays can see it); truncation is
// set by the environment itself, at 1600 steps or 2000 in hardcore (Gymnasium's TimeLimit),
// counting Step calls after Reset. Stepping on after termination is allowed, as in Gymnasium: a
// fallen walker keeps returning -100 and terminated.
//
// Movable, not copyable. Thread-compatible; one instance per environment slot.

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "common/random.h"
#include "env/bipedal_walker_world.h"
#include "env/context_feature.h"
#include "env/state_projection.h"
#include "env/step_result.h"

namespace dcs::env {

class Canvas;  // env/raster.h

class BipedalWalker final {
 public:
  static constexpr absl::string_view kName = "bipedal_walker";
  // The shape every DCS environment declares (env/dynamic_context_env.h uses it).
  using Observation = float;
  using ActionElement = float;
  static constexpr int kObservationSize = 24;
  static constexpr int kActionSize = 4;
  // Action bounds: [hip0, knee0, hip1, knee1] in [-1, 1] (torques are clipped to them).
  static constexpr double kActionLow[kActionSize] = {-1, -1, -1, -1};
  static constexpr double kActionHigh[kActionSize] = {1, 1, 1, 1};
  // The normal-terrain limit; a hardcore episode runs to kMaxHardcoreEpisodeSteps. The
  // environment truncates by itself (max_episode_steps() gives the running episode's limit).
  static constexpr int kMaxEpisodeSteps = 1600;
  static constexpr int kMaxHardcoreEpisodeSteps = 2000;

  // Feature indices into Features(): CARL's order, then the payload and hardcore. "Step": a
  // change takes effect at the next Step; "reset": at the next Reset.
  enum Feature : int {
    kFps,              // steps per second (time step, velocity scaling); step
    kScale,            // pixels per metre (hull size, reward and observation scaling); reset
    kGravityX,         // m/s^2; step
    kGravityY,         // m/s^2; step
    kFriction,         // terrain friction, also of existing contacts; step
    kTerrainStep,      // m between terrain points; reset
    kTerrainLength,    // terrain points (integer); reset
    kTerrainHeight,    // m; reset
    kTerrainGrass,     // grass stretch length bound, points (integer); reset
    kTerrainStartpad,  // flat points at the start; reset
    kMotorsTorque,     // N m at |action| = 1 (motors and the torque cost); step
    kSpeedHip,         // rad/s (motor speed, joint-speed scaling); step
    kSpeedKnee,        // rad/s (motor speed, joint-speed scaling); step
    kLidarRange,       // m; step
    kLegDown,          // m; reset
    kLegW,             // m; reset
    kLegH,             // m; reset
    kInitialRandom,    // N, bound of the initial push; reset
    kViewportW,        // px (integer; observation scaling, view); reset
    kViewportH,        // px (integer; observation scaling, clouds, view); reset
    kComX,             // m, payload position along the hull's forward axis; step
    kPayloadMass,      // kg, 0 = no payload; step
    kPayloadRadius,    // m; step
    kHardcore,         // 0 or 1 (terrain and time limit); reset
    kNumFeatures
  };

  // The features with CARL's bounds (COM_X: [-2, 2], the paper's sensor bounds, wide enough for
  // the evaluation grid up to +-1.7); normalisation bounds equal the physical ones.
  static const ContextSpace& Features();

  // The coverage diagnostic's four projections (docs/reference.md, "Coverage") over Gymnasium's
  // declared bounds (docs/reference.md, "Coverage"): "inter_leg" hip 1 vs hip 2 angle (30^2),
  // "joints" the hip and knee angles of both legs (12^4), "posture" hull and both hip angles
  // (15^3), "leg1_phase" hip 1 angle vs speed (30^2).
  static const std::vector<StateProjection>& CoverageProjections();

  // OK if every value is valid for its feature and the integer features (TERRAIN_LENGTH,
  // TERRAIN_GRASS, VIEWPORT_W, VIEWPORT_H, HARDCORE) hold integers.
  static absl::Status ValidateContext(std::span<const double> values);

  // The default context, no world built yet: call Reset before Step.
  BipedalWalker();

  double GetFeature(int feature) const { return features_[feature]; }
  // Takes effect as the file comment says. REQUIRES: `value` valid for `feature`
  // (ContextSpace::Validate); a non-integer for an integer feature is truncated where used.
  void SetFeature(int feature, double value);

  // Builds a new world from the current features, drawing from `random`, and writes the
  // observation of the internal zero-action step.
  void Reset(Random& random, std::span<float, kObservationSize> observation);

  // One step. REQUIRES: Reset was called; finite actions.
  StepResult Step(std::span<const float, kActionSize> action,
                  std::span<float, kObservationSize> observation);

  // Draws the scene as Gymnasium's human render does: sky, clouds, terrain fill
  // and edges, hardcore obstacles, the lidar ray `lidar_ray` in red if it is in [0, 10), legs,
  // hull and payload, and the start flag, for the camera at the current scroll. Meant for a
  // VIEWPORT_W x VIEWPORT_H canvas (600 x 400 by default); another size keeps the scale,
  // anchored at the bottom-left. No anti-aliasing. REQUIRES: Reset was called.
  static constexpr int kRenderWidth = 600;
  static constexpr int kRenderHeight = 400;
  static constexpr int kRenderFps = 50;  // Gymnasium's metadata["render_fps"]
  void Render(Canvas& canvas, int lidar_ray = -1) const;

  // The running episode's time limit and the Step calls made since Reset.
  int max_episode_steps() const { return max_episode_steps_; }
  int elapsed_steps() const { return elapsed_steps_; }
  // The camera's left edge, m (Gymnasium's scroll).
  double scroll() const { return scroll_; }
  const WalkerWorld& world() const { return *world_; }

 private:
  // The physics step and everything after it (observation, reward, termination), shared by
  // Step and the internal step of Reset.
  StepResult Advance(std::span<const float, kActionSize> action,
                     std::span<float, kObservationSize> observation);
  void ApplyPendingChanges();
  WalkerPayload Payload() const;

  std::array<double, kNumFeatures> features_;
  std::unique_ptr<WalkerWorld> world_;
  // Latched at Reset from the features.
  double scale_ = 30;
  double viewport_w_ = 600;
  double viewport_h_ = 400;
  double terminal_x_ = 0;  // (TERRAIN_LENGTH - TERRAIN_GRASS) * TERRAIN_STEP
  int max_episode_steps_ = kMaxEpisodeSteps;
  // Episode state.
  bool built_ = false;
  bool has_prev_shaping_ = false;
  double prev_shaping_ = 0;
  double scroll_ = 0;
  int elapsed_steps_ = 0;
  // Feature changes waiting for the next Step.
  bool gravity_changed_ = false;
  bool friction_changed_ = false;
  bool payload_changed_ = false;
};

}  // namespace dcs::env

#endif  // DCS_ENV_BIPEDAL_WALKER_H_
