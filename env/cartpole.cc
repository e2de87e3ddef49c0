// Copyright 2026 The DCS Authors.
#include "env/cartpole.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"

namespace dcs::env {

const ContextSpace& CartPole::Features() {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Bounds: CARL v1.1.1. Normalisation bounds: the paper's for the length; for the others,
  // the physical bounds where finite, else a physically plausible range.
  static const ContextSpace* features = new ContextSpace({
      {"gravity", "gravitational acceleration, m/s^2", 9.8, 0.1, kInf, 0.1, 25.0},
      {"masscart", "cart mass, kg", 1.0, 0.1, 10.0, 0.1, 10.0},
      {"masspole", "pole mass, kg", 0.1, 0.01, 1.0, 0.01, 1.0},
      {"length", "half the pole length, m", 0.5, 0.05, 5.0, 0.05, 2.0},
      {"force_mag", "push force, N", 10.0, 1.0, 100.0, 1.0, 100.0},
      {"tau", "seconds per step", 0.02, 0.002, 0.2, 0.002, 0.2},
      {"initial_state_lower", "lower bound of the reset state, every dimension", -0.1, -kInf,
       kInf, -1.0, 1.0},
      {"initial_state_upper", "upper bound of the reset state, every dimension", 0.1, -kInf,
       kInf, -1.0, 1.0},
  });
  return *features;
}

const std::vector<StateProjection>& CartPole::CoverageProjections() {
  // Cart position, cart velocity, pole angle, pole angular velocity: the paper's "physically
  // plausible ranges" (its observation bounds are infinite for the velocities).
  static const auto* projections = new std::vector<StateProjection>{
      {.name = "state",
       .dims = {0, 1, 2, 3},
       .bins = 12,
       .low = {-2.5, -3.5, -0.30, -4.0},
       .high = {2.5, 3.5, 0.30, 4.0}}};
  return *projections;
}

absl::Status CartPole::ValidateContext(std::span<const double> values) {
  for (int i = 0; i < kNumFeatures; ++i) DCS_RETURN_IF_ERROR(Features().Validate(i, values[i]));
  if (values[kInitialStateLower] > values[kInitialStateUpper]) {
    return absl::InvalidArgumentError(absl::StrCat(
        "initial_state_lower (", values[kInitialStateLower],
        ") must not exceed initial_state_upper (", values[kInitialStateUpper], ")"));
  }
  return absl::OkStatus();
}

CartPole::CartPole() {
  for (int i = 0; i < kNumFeatures; ++i) features_[i] = Features().feature(i).default_value;
  SetFeature(kLength, features_[kLength]);  // derives total_mass_ and polemass_length_
}

void CartPole::SetFeature(int feature, double value) {
  features_[feature] = value;
  total_mass_ = features_[kMassPole] + features_[kMassCart];
  polemass_length_ = features_[kMassPole] * features_[kLength];
}

void CartPole::Reset(Random& random, std::span<float, kObservationSize> observation) {
  const double low = features_[kInitialStateLower];
  const double high = features_[kInitialStateUpper];
  CartPoleState state;
  state.x = random.Uniform(low, high);
  state.x_dot = random.Uniform(low, high);
  state.theta = random.Uniform(low, high);
  state.theta_dot = random.Uniform(low, high);
  ResetTo(state, observation);
}

void CartPole::ResetTo(const CartPoleState& state,
                       std::span<float, kObservationSize> observation) {
  state_ = state;
  elapsed_steps_ = 0;
  terminated_before_ = false;
  WriteObservation(observation);
}

StepResult CartPole::Step(std::span<const int32_t, kActionSize> action,
                          std::span<float, kObservationSize> observation) {
  // Gymnasium CartPoleEnv.step, term by term and in its order, so results agree to the ulp.
  const double force = action[0] == 1 ? features_[kForceMag] : -features_[kForceMag];
  const double length = features_[kLength];
  const double costheta = std::cos(state_.theta);
  const double sintheta = std::sin(state_.theta);
  const double temp =
      (force + polemass_length_ * (state_.theta_dot * state_.theta_dot) * sintheta) / total_mass_;
  const double thetaacc =
      (features_[kGravity] * sintheta - costheta * temp) /
      (length * (4.0 / 3.0 - features_[kMassPole] * (costheta * costheta) / total_mass_));
  const double xacc = temp - polemass_length_ * thetaacc * costheta / total_mass_;

  const double tau = features_[kTau];
  state_.x = state_.x + tau * state_.x_dot;
  state_.x_dot = state_.x_dot + tau * xacc;
  state_.theta = state_.theta + tau * state_.theta_dot;
  state_.theta_dot = state_.theta_dot + tau * thetaacc;

  StepResult result;
  result.terminated = state_.x < -kXThreshold || state_.x > kXThreshold ||
                      state_.theta < -kThetaThreshold || state_.theta > kThetaThreshold;
  if (!result.terminated) {
    result.reward = 1.0;
  } else if (!terminated_before_) {
    result.reward = 1.0;  // the first terminating step still earns its reward
    terminated_before_ = true;
  }
  result.truncated = ++elapsed_steps_ >= kMaxEpisodeSteps;
  WriteObservation(observation);
  return result;
}

void CartPole::Render(Canvas& canvas) const {
  // Gymnasium draws with y up and flips the image; here y is down from the start.
  constexpr double kScale = kRenderWidth / (2 * kXThreshold);  // 125 px per metre
  constexpr double kCartY = kRenderHeight - 100.0;               // the track line
  const double cart_x = state_.x * kScale + kRenderWidth / 2.0;
  canvas.Clear({255, 255, 255});
  canvas.FillRect(0, kCartY, kRenderWidth, kCartY + 1, {0, 0, 0});
  canvas.FillRect(cart_x - 25, kCartY - 15, cart_x + 25, kCartY + 15, {0, 0, 0});

  // The pole: 10 px wide, from 5 px below the axle to its tip, turned by theta (clockwise on
  // screen for a positive angle, which leans the pole to the right).
  const double pivot_y = kCartY - 7.5;
  const double pole_length = kScale * 2 * features_[kLength];
  const double c = std::cos(state_.theta);
  const double s = std::sin(state_.theta);
  auto turned = [&](double along, double across) {
    return PixelPoint{cart_x + across * c + along * s, pivot_y + across * s - along * c};
  };
  const PixelPoint pole[] = {turned(-5, -5), turned(-5, 5), turned(pole_length - 5, 5),
                             turned(pole_length - 5, -5)};
  canvas.FillPolygon(pole, {202, 152, 101});

  PixelPoint axle[16];
  for (int i = 0; i < 16; ++i) {
    const double angle = 2 * std::numbers::pi * i / 16;
    axle[i] = {cart_x + 5 * std::cos(angle), pivot_y + 5 * std::sin(angle)};
  }
  canvas.FillPolygon(axle, {129, 132, 203});
}

void CartPole::WriteObservation(std::span<float, kObservationSize> observation) const {
  observation[0] = static_cast<float>(state_.x);
  observation[1] = static_cast<float>(state_.x_dot);
  observation[2] = static_cast<float>(state_.theta);
  observation[3] = static_cast<float>(state_.theta_dot);
}

}  // namespace dcs::env
