// Copyright 2026 The DCS Authors.
#include "env/bipedal_walker.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"

namespace dcs::env {

const ContextSpace& BipedalWalker::Features() {
  // Bounds and defaults: CARL v1.1.1 (TERRAIN_HEIGHT's default: Gymnasium's), the reference's
  // COM_X widened to the paper's sensor bounds, the paper's payload. Normalisation bounds: the
  // physical bounds, all finite.
  static const ContextSpace* features = new ContextSpace({
      {"FPS", "simulation steps per second", 50.0, 1.0, 500.0, 1.0, 500.0},
      {"SCALE", "pixels per metre: hull size, reward and observation scaling", 30.0, 1.0, 100.0,
       1.0, 100.0},
      {"GRAVITY_X", "horizontal gravity, m/s^2", 0.0, -20.0, 20.0, -20.0, 20.0},
      {"GRAVITY_Y", "vertical gravity, m/s^2", -10.0, -20.0, -0.01, -20.0, -0.01},
      {"FRICTION", "terrain friction coefficient", 2.5, 0.0, 10.0, 0.0, 10.0},
      {"TERRAIN_STEP", "distance between terrain points, m", 14.0 / 30.0, 0.25, 1.0, 0.25, 1.0},
      {"TERRAIN_LENGTH", "terrain points (integer)", 200.0, 100.0, 500.0, 100.0, 500.0},
      {"TERRAIN_HEIGHT", "height of the start pad, m (Gymnasium's 400/30/4, not CARL's 5)",
       400.0 / 30.0 / 4.0, 3.0, 10.0, 3.0, 10.0},
      {"TERRAIN_GRASS", "grass stretches last [G/2, G) points (integer)", 10.0, 5.0, 15.0, 5.0,
       15.0},
      {"TERRAIN_STARTPAD", "flat terrain points at the start", 20.0, 10.0, 30.0, 10.0, 30.0},
      {"MOTORS_TORQUE", "motor torque at |action| = 1, N m", 80.0, 0.01, 200.0, 0.01, 200.0},
      {"SPEED_HIP", "hip motor speed, rad/s", 4.0, 0.01, 15.0, 0.01, 15.0},
      {"SPEED_KNEE", "knee motor speed, rad/s", 6.0, 0.01, 15.0, 0.01, 15.0},
      {"LIDAR_RANGE", "lidar ray length, m", 160.0 / 30.0, 0.01, 20.0, 0.01, 20.0},
      {"LEG_DOWN", "hip anchor height below the hull origin, m (negative)", -8.0 / 30.0, -2.0,
       -0.25, -2.0, -0.25},
      {"LEG_W", "upper leg width, m", 8.0 / 30.0, 0.25, 0.5, 0.25, 0.5},
      {"LEG_H", "leg segment length, m", 34.0 / 30.0, 0.25, 2.0, 0.25, 2.0},
      {"INITIAL_RANDOM", "bound of the random initial push, N", 5.0, 0.0, 50.0, 0.0, 50.0},
      {"VIEWPORT_W", "view width, px (integer)", 600.0, 400.0, 1000.0, 400.0, 1000.0},
      {"VIEWPORT_H", "view height, px (integer)", 400.0, 200.0, 800.0, 200.0, 800.0},
      {"COM_X", "payload position along the hull's forward axis, m", 0.0, -2.0, 2.0, -2.0, 2.0},
      {"PAYLOAD_MASS", "payload mass, kg (0: no payload)", 2.0, 0.0, 20.0, 0.0, 20.0},
      {"PAYLOAD_RADIUS", "payload radius, m", 0.5, 0.01, 2.0, 0.01, 2.0},
      {"HARDCORE", "1: stumps, stairs and pits and a 2000-step limit; 0: normal", 0.0, 0.0, 1.0,
       0.0, 1.0},
  });
  return *features;
}

const std::vector<StateProjection>& BipedalWalker::CoverageProjections() {
  // Gymnasium's observation bounds are float32: pi as the float the tracker reads.
  constexpr double kPi = static_cast<float>(std::numbers::pi);
  constexpr int kHull = 0, kHip1 = 4, kHip1Speed = 5, kKnee1 = 6, kHip2 = 9, kKnee2 = 11;
  static const auto* projections = new std::vector<StateProjection>{
      {.name = "inter_leg", .dims = {kHip1, kHip2}, .bins = 30, .low = {-kPi, -kPi},
       .high = {kPi, kPi}},
      {.name = "joints", .dims = {kHip1, kKnee1, kHip2, kKnee2}, .bins = 12,
       .low = {-kPi, -kPi, -kPi, -kPi}, .high = {kPi, kPi, kPi, kPi}},
      {.name = "posture", .dims = {kHull, kHip1, kHip2}, .bins = 15, .low = {-kPi, -kPi, -kPi},
       .high = {kPi, kPi, kPi}},
      {.name = "leg1_phase", .dims = {kHip1, kHip1Speed}, .bins = 30, .low = {-kPi, -5.0},
       .high = {kPi, 5.0}}};
  return *projections;
}

absl::Status BipedalWalker::ValidateContext(std::span<const double> values) {
  for (int i = 0; i < kNumFeatures; ++i) DCS_RETURN_IF_ERROR(Features().Validate(i, values[i]));
  for (const int i : {kTerrainLength, kTerrainGrass, kViewportW, kViewportH, kHardcore}) {
    if (values[i] != std::trunc(values[i])) {
      return absl::InvalidArgumentError(
          absl::StrCat(Features().feature(i).name, " must be an integer, got ", values[i]));
    }
  }
  return absl::OkStatus();
}

BipedalWalker::BipedalWalker() : world_(std::make_unique<WalkerWorld>()) {
  for (int i = 0; i < kNumFeatures; ++i) features_[i] = Features().feature(i).default_value;
}

void BipedalWalker::SetFeature(int feature, double value) {
  if (features_[feature] == value) return;
  features_[feature] = value;
  switch (feature) {
    case kGravityX:
    case kGravityY:
      gravity_changed_ = true;
      break;
    case kFriction:
      friction_changed_ = true;
      break;
    case kComX:
    case kPayloadMass:
    case kPayloadRadius:
      payload_changed_ = true;
      break;
    default:  // read at every step, or latched at the next reset
      break;
  }
}

WalkerPayload BipedalWalker::Payload() const {
  return {.com_x = features_[kComX],
          .mass = features_[kPayloadMass],
          .radius = features_[kPayloadRadius]};
}

void BipedalWalker::Reset(Random& random, std::span<float, kObservationSize> observation) {
  const std::array<double, kNumFeatures>& f = features_;
  const bool hardcore = f[kHardcore] >= 0.5;
  const WalkerGeometry geometry = {
      .scale = f[kScale],
      .terrain_step = f[kTerrainStep],
      .terrain_length = static_cast<int>(f[kTerrainLength]),
      .terrain_height = f[kTerrainHeight],
      .terrain_grass = static_cast<int>(f[kTerrainGrass]),
      .terrain_startpad = f[kTerrainStartpad],
      .leg_down = f[kLegDown],
      .leg_w = f[kLegW],
      .leg_h = f[kLegH],
      .initial_random = f[kInitialRandom],
      .viewport_h = static_cast<double>(static_cast<int>(f[kViewportH])),
      .hardcore = hardcore,
  };
  scale_ = geometry.scale;
  viewport_w_ = static_cast<int>(f[kViewportW]);
  viewport_h_ = geometry.viewport_h;
  terminal_x_ = (geometry.terrain_length - geometry.terrain_grass) * geometry.terrain_step;
  max_episode_steps_ = hardcore ? kMaxHardcoreEpisodeSteps : kMaxEpisodeSteps;

  world_->SetGravity(f[kGravityX], f[kGravityY]);
  world_->Build(geometry, f[kFriction], f[kMotorsTorque], random);
  built_ = true;
  has_prev_shaping_ = false;
  scroll_ = 0;
  elapsed_steps_ = 0;
  // Gymnasium's internal step: its reward sets prev_shaping, its termination is ignored.
  constexpr std::array<float, kActionSize> kZero = {0, 0, 0, 0};
  Advance(kZero, observation);
  world_->SetPayload(Payload());
  gravity_changed_ = friction_changed_ = payload_changed_ = false;
}

void BipedalWalker::ApplyPendingChanges() {
  if (gravity_changed_) world_->SetGravity(features_[kGravityX], features_[kGravityY]);
  if (friction_changed_) world_->SetTerrainFriction(features_[kFriction]);
  if (payload_changed_) world_->SetPayload(Payload());
  gravity_changed_ = friction_changed_ = payload_changed_ = false;
}

StepResult BipedalWalker::Step(std::span<const float, kActionSize> action,
                               std::span<float, kObservationSize> observation) {
  assert(built_);
  ApplyPendingChanges();
  StepResult result = Advance(action, observation);
  result.truncated = ++elapsed_steps_ >= max_episode_steps_;
  return result;
}

// BipedalWalker.step (gymnasium/envs/box2d/bipedal_walker.py), environment arithmetic in double.
StepResult BipedalWalker::Advance(std::span<const float, kActionSize> action,
                                  std::span<float, kObservationSize> observation) {
  const std::array<double, kNumFeatures>& f = features_;
  const double fps = f[kFps];
  const double speed_hip = f[kSpeedHip];
  const double speed_knee = f[kSpeedKnee];
  const double motors_torque = f[kMotorsTorque];
  world_->SetMotors(action, speed_hip, speed_knee, motors_torque);
  world_->Step(1.0 / fps);

  const b2Body* hull = world_->hull();
  const b2Vec2 pos = hull->GetPosition();
  const b2Vec2 vel = hull->GetLinearVelocity();
  world_->CastLidar(f[kLidarRange], observation.subspan<14, WalkerWorld::kNumLidar>());

  const double angle = hull->GetAngle();
  observation[0] = static_cast<float>(angle);
  observation[1] = static_cast<float>(2.0 * hull->GetAngularVelocity() / fps);
  observation[2] = static_cast<float>(0.3 * vel.x * (viewport_w_ / scale_) / fps);
  observation[3] = static_cast<float>(0.3 * vel.y * (viewport_h_ / scale_) / fps);
  for (int side = 0; side < 2; ++side) {
    const b2RevoluteJoint* hip = world_->joint(2 * side);
    const b2RevoluteJoint* knee = world_->joint(2 * side + 1);
    const int base = 4 + 5 * side;
    observation[base] = static_cast<float>(static_cast<double>(hip->GetJointAngle()));
    observation[base + 1] = static_cast<float>(hip->GetJointSpeed() / speed_hip);
    observation[base + 2] = static_cast<float>(knee->GetJointAngle() + 1.0);
    observation[base + 3] = static_cast<float>(knee->GetJointSpeed() / speed_knee);
    observation[base + 4] = world_->ground_contact(side) ? 1.0f : 0.0f;
  }

  scroll_ = pos.x - viewport_w_ / scale_ / 5;

  // Moving forward earns 130 / SCALE per metre (about 300 over the course); a tilted head costs.
  const double shaping = 130 * static_cast<double>(pos.x) / scale_ - 5.0 * std::abs(angle);
  StepResult result;
  if (has_prev_shaping_) result.reward = shaping - prev_shaping_;
  prev_shaping_ = shaping;
  has_prev_shaping_ = true;
  for (const float a : action) {
    result.reward -=
        0.00035 * motors_torque * std::clamp(std::abs(static_cast<double>(a)), 0.0, 1.0);
  }
  if (world_->game_over() || pos.x < 0) {
    result.reward = -100;
    result.terminated = true;
  }
  if (pos.x > terminal_x_) result.terminated = true;
  return result;
}

}  // namespace dcs::env
