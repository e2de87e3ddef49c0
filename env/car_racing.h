// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_CAR_RACING_H_
#define DCS_ENV_CAR_RACING_H_

// Gymnasium's CarRacing-v3 (1.4.0, gymnasium/envs/box2d/car_racing.py) on Box2D 2.4.1, with DCS's
// context features: the paper's payload (COM_X, COM_Y; docs/reference.md, "Context features and
// payloads") and a few physical parameters of the car. Observation: the 96x96 RGB picture (uint8, H
// x W x RGB, row 0 at the top). Reward: +1000/N for each newly visited of the N track tiles, -0.1
// per step; -100 (and termination) for leaving the playfield; termination when every tile has been
// visited; truncation at 1000 steps. The reset performs Gymnasium's internal first step, whose tile
// credit is paid in the first real step. Reset draws from `Random` exactly as Gymnasium draws from
// its np_random, so a numpy-exact generator seeded as Gymnasium seeds gives Gymnasium's track.
//
// Context features (Features()); every change takes effect at the next Step:
//   COM_X, COM_Y     payload position in the hull frame, m. The car points along its local +y
//                    axis, so COM_X is LATERAL (positive to the driver's right) and COM_Y is
//                    LONGITUDINAL (positive forward). This is the reference implementation's
//                    mapping; the paper calls COM_X "longitudinal" and COM_Y "lateral"
//                    (docs/reference.md, "Context features and payloads"): in reports, label the
//                    axes by their body-frame meaning.
//   PAYLOAD_MASS     kg (default 1.0, the paper's); 0 removes the payload.
//   PAYLOAD_RADIUS   m (default 0.5, the paper's).
//                    A change of any payload feature re-creates the payload body (a 16-gon
//                    welded to the hull, drawn in cyan, carrying the hull's velocities) at the
//                    start of the next Step, so the mass data are recomputed for that step.
//                    The default context thus carries 1 kg at the hull origin; set
//                    PAYLOAD_MASS = 0 for Gymnasium's own car. As in the reference, the
//                    payload keeps Box2D's default collision filter: placed over a wheel
//                    (|COM_X| > ~0.3 together with |COM_Y| > ~0.55) it collides with it.
//   ENGINE_POWER, FRICTION_LIMIT, BRAKE_FORCE, WHEEL_MOMENT_OF_INERTIA
//                    car_dynamics.py's ENGINE_POWER (40000), FRICTION_LIMIT (400, tyre grip on
//                    the road; on grass 0.6 of it), BRAKE_FORCE (15) and
//                    WHEEL_MOMENT_OF_INERTIA (1.6), read by the wheel model at every step.
//   LAP_COMPLETE_PERCENT
//                    Gymnasium's constructor argument (0.95), read when tile 0 is first visited.
// Nothing is structural: no feature waits for the next reset.
//
// DCS deviations from Gymnasium, none of which changes the car's dynamics: a fresh b2World per
// reset (Gymnasium reuses one; a fresh one makes an episode a function of its seed alone); the
// picture is drawn without anti-aliasing into a supersampled canvas and box-filtered (see
// env/car_racing_render.h), with a block font for the score; no skid marks (Gymnasium draws
// none in the observation either). From the reference payload mechanism (docs/reference.md,
// "Context features and payloads"): the payload exists from the reset's internal step on (the
// reference attaches it after reset), its mass is exactly PAYLOAD_MASS (the reference's density
// makes its 16-gon 2.5% lighter), and the 16-gon is built from four convex pieces (Box2D 2.4.1
// polygons have at most 8 vertices; mass, centre and inertia are those of the 16-gon).
//
// CarRacing and CarRacingDiscrete are thread-compatible and movable (the Box2D world lives on
// the heap). A moved-from object may only be destroyed or assigned to.

#include <cstdint>
#include <memory>
#include <span>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "common/random.h"
#include "env/car_dynamics.h"
#include "env/car_racing_track.h"
#include "env/context_feature.h"
#include "env/raster.h"
#include "env/step_result.h"

namespace dcs::env {

struct CarRacingOptions {
  // Gymnasium's domain_randomize: road, background and grass colours drawn at every reset,
  // before the track (7 draws).
  bool domain_randomize = false;
  // Observation quality: the picture is drawn at this many times 96 pixels per axis and then
  // box-filtered. 2 is fast (see bench/env/car_racing_benchmark.cc); 4 is closer to pygame's
  // area average of the 1000x800 window. 1..8.
  int supersample = 2;
};

// The feature indices shared by CarRacing and CarRacingDiscrete.
struct CarRacingFeatureIndex {
  enum Feature : int {
    kComX,                  // m, hull-local x (lateral)
    kComY,                  // m, hull-local y (longitudinal)
    kPayloadMass,           // kg, 0 = no payload
    kPayloadRadius,         // m
    kEnginePower,           // W per driven wheel
    kFrictionLimit,         // N
    kBrakeForce,            // rad/s per step
    kWheelMomentOfInertia,  // kg m^2
    kLapCompletePercent,    // fraction of tiles
    kNumFeatures
  };
};

class CarRacing final : public CarRacingFeatureIndex {
 public:
  static constexpr absl::string_view kName = "car_racing";
  using Observation = uint8_t;
  using ActionElement = float;  // [steer (-1 full left .. +1 full right), gas, brake]
  // An image observation (what env/dynamic_context_env.h's users and `dcs env render` look for).
  static constexpr int kImageHeight = 96;
  static constexpr int kImageWidth = 96;
  static constexpr int kImageChannels = 3;
  static constexpr int kObservationSize = kImageHeight * kImageWidth * kImageChannels;
  static constexpr int kActionSize = 3;
  static constexpr double kActionLow[kActionSize] = {-1, 0, 0};
  static constexpr double kActionHigh[kActionSize] = {1, 1, 1};
  static constexpr int kMaxEpisodeSteps = 1000;
  static constexpr double kFps = 50;
  // Gymnasium's rgb_array frame (the 1000x800 window shrunk to 600x400), for Render.
  static constexpr int kRenderWidth = 600;
  static constexpr int kRenderHeight = 400;
  static constexpr int kRenderFps = 50;  // Gymnasium's metadata["render_fps"]

  // The features above, with Gymnasium's (or the paper's) values as defaults; the paper's
  // sensor bounds (-2, 2) for COM_X and COM_Y, the reference feature bounds [-5, 5] and
  // [-3, 3] as physical bounds.
  static const ContextSpace& Features();

  // OK if every value is valid for its feature.
  static absl::Status ValidateContext(std::span<const double> values);

  // Default context; no track until the first Reset.
  CarRacing();
  explicit CarRacing(const CarRacingOptions& options);
  ~CarRacing();
  CarRacing(CarRacing&&) noexcept;
  CarRacing& operator=(CarRacing&&) noexcept;

  double GetFeature(int feature) const;
  // Takes effect at the next Step (see the file comment). REQUIRES: `value` valid for
  // `feature` (ContextSpace::Validate).
  void SetFeature(int feature, double value);

  // Generates a new track (retrying as Gymnasium does), places the car at its start, runs the
  // internal first step and writes its observation.
  void Reset(Random& random, std::span<uint8_t, kObservationSize> observation);

  // One step of 1/50 s with `action` = [steer, gas, brake] (cast to double; gas is clipped to
  // [0, 1] and ramps up by at most 0.1 per step; steer and brake are used as given). Stepping on
  // after termination is allowed, as in Gymnasium. REQUIRES: Reset was called.
  StepResult Step(std::span<const float, kActionSize> action,
                  std::span<uint8_t, kObservationSize> observation);

  // Read-only state, for scripted drivers, tests and tools. Valid from the first Reset; the
  // references stay valid until the next Reset.
  const Track& track() const;
  const Car& car() const;
  int num_tiles() const { return track().size(); }
  int tiles_visited() const;
  bool tile_visited(int tile) const;
  double total_reward() const;  // Gymnasium's self.reward: tile credit minus 0.1 per step
  double time() const;          // simulated seconds, including the reset step
  int elapsed_steps() const;    // Step calls since Reset

  // Draws the current scene as Gymnasium's 1000x800 window scaled to `canvas` (600x400 is the
  // rgb_array frame; any size works, each axis scaled on its own). REQUIRES: Reset was called.
  void Render(Canvas& canvas) const;

 private:
  friend class CarRacingDiscrete;
  struct State;

  // Gymnasium's step: with `controls` = nullptr (the reset's internal step) the controls stay
  // as they are and no reward or termination is computed; otherwise controls = {steer target,
  // gas, brake} are passed to the car's setters first.
  StepResult StepWithControls(const double* controls,
                              std::span<uint8_t, kObservationSize> observation);

  std::unique_ptr<State> state_;
};

// CarRacing with Gymnasium's discrete actions (continuous=False): 0 nothing, 1 steer right,
// 2 steer left, 3 gas, 4 brake, which set steer -0.6 / +0.6, gas 0.2 and brake 0.8 (the
// controls not named are set to 0 every step). Everything else as CarRacing.
class CarRacingDiscrete final : public CarRacingFeatureIndex {
 public:
  static constexpr absl::string_view kName = "car_racing_discrete";
  using Observation = uint8_t;
  using ActionElement = int32_t;
  static constexpr int kImageHeight = CarRacing::kImageHeight;
  static constexpr int kImageWidth = CarRacing::kImageWidth;
  static constexpr int kImageChannels = CarRacing::kImageChannels;
  static constexpr int kObservationSize = CarRacing::kObservationSize;
  static constexpr int kActionSize = 1;
  static constexpr int kNumActions = 5;
  static constexpr int kMaxEpisodeSteps = CarRacing::kMaxEpisodeSteps;
  static constexpr int kRenderWidth = CarRacing::kRenderWidth;
  static constexpr int kRenderHeight = CarRacing::kRenderHeight;
  static constexpr int kRenderFps = CarRacing::kRenderFps;

  static const ContextSpace& Features() { return CarRacing::Features(); }
  static absl::Status ValidateContext(std::span<const double> values) {
    return CarRacing::ValidateContext(values);
  }

  CarRacingDiscrete() = default;
  explicit CarRacingDiscrete(const CarRacingOptions& options) : env_(options) {}

  double GetFeature(int feature) const { return env_.GetFeature(feature); }
  void SetFeature(int feature, double value) { env_.SetFeature(feature, value); }
  void Reset(Random& random, std::span<uint8_t, kObservationSize> observation) {
    env_.Reset(random, observation);
  }
  // REQUIRES: 0 <= action[0] < kNumActions (Gymnasium raises InvalidAction).
  StepResult Step(std::span<const int32_t, kActionSize> action,
                  std::span<uint8_t, kObservationSize> observation);
  void Render(Canvas& canvas) const { env_.Render(canvas); }

  // The continuous environment underneath, for its read-only accessors.
  const CarRacing& base() const { return env_; }

 private:
  CarRacing env_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_CAR_RACING_H_
