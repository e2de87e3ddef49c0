// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_CAR_DYNAMICS_H_
#define DCS_ENV_CAR_DYNAMICS_H_

// The car of Gymnasium's CarRacing-v3 (gymnasium/envs/box2d/car_dynamics.py): a hull of
// four polygons, four wheels on motorised, limited revolute joints, and the wheel model that
// turns engine, brake and tyre slip into forces applied to the wheels' centres. Plus DCS's
// payload (docs/reference.md, "Context features and payloads"): a 16-gon body welded to the hull at
// a hull-local point.
//
// The car's bodies belong to the b2World given at construction, which must outlive the Car;
// the Car destroys only its payload body (when it is replaced), never the rest (destroy the
// world to destroy the car). Confined to one thread, like its world.
//
// The car points along its local +y axis (front wheels at y = +1.6): local x is lateral (to the
// right of the driver), local y longitudinal.

#include <array>
#include <cstdint>

#include "box2d/box2d.h"

namespace dcs::env {

// What a Box2D fixture's user data (b2FixtureUserData::pointer) says about it, for the contact
// listener: a road tile or a wheel, with its index. 0 means neither (hull, payload).
enum class CarRacingFixtureKind : uintptr_t { kNone = 0, kTile = 1, kWheel = 2 };
inline uintptr_t CarRacingFixtureTag(CarRacingFixtureKind kind, int index) {
  return (static_cast<uintptr_t>(kind) << 24) | static_cast<uintptr_t>(index);
}
inline CarRacingFixtureKind CarRacingFixtureTagKind(uintptr_t tag) {
  return static_cast<CarRacingFixtureKind>(tag >> 24);
}
inline int CarRacingFixtureTagIndex(uintptr_t tag) { return static_cast<int>(tag & 0xFFFFFF); }

// car_dynamics.py constants, in world units (SIZE = 0.02 per pixel of the car's drawing).
inline constexpr double kCarSize = 0.02;
inline constexpr double kCarEnginePower = 100000000 * kCarSize * kCarSize;      // 40000
inline constexpr double kCarWheelMomentOfInertia = 4000 * kCarSize * kCarSize;  // 1.6
inline constexpr double kCarFrictionLimit = 1000000 * kCarSize * kCarSize;      // 400
inline constexpr double kCarBrakeForce = 15;  // rad/s of wheel speed removed per step at 1
inline constexpr double kCarGrassFrictionFactor = 0.6;
inline constexpr double kCarWheelRadius = 27 * kCarSize;     // 0.54
inline constexpr double kCarWheelHalfWidth = 14 * kCarSize;  // 0.28

// Parameters of the wheel model read at every Car::Step, so a change takes effect at once.
struct CarParams {
  double engine_power = kCarEnginePower;                      // per driven wheel, W
  double wheel_moment_of_inertia = kCarWheelMomentOfInertia;  // kg m^2
  double friction_limit = kCarFrictionLimit;  // max tyre force on road, N (grass: 0.6 of it)
  double brake_force = kCarBrakeForce;        // rad/s per step at brake = 1 (below 0.9)
};

// A payload welded to the hull at hull-local (x, y): a regular 16-gon of circumradius `radius`
// whose mass is exactly `mass` (the reference sets density mass / (pi r^2), which makes the
// 16-gon 2.5% lighter than `mass`; DCS keeps the nominal mass). mass == 0: no payload.
struct PayloadSpec {
  double x = 0;  // m, hull-local, lateral (to the right)
  double y = 0;  // m, hull-local, longitudinal (forward)
  double mass = 0;
  double radius = 0.5;

  bool operator==(const PayloadSpec&) const = default;
};

class Car {
 public:
  struct Wheel {
    b2Body* body = nullptr;
    b2RevoluteJoint* joint = nullptr;
    double gas = 0;  // only the rear wheels (2, 3) are driven
    double brake = 0;
    double steer = 0;  // target joint angle, rad (front wheels 0, 1 only); positive turns left
    double phase = 0;  // rad, for the stripe drawing only
    double omega = 0;  // wheel angular speed, rad/s
    int tiles = 0;     // road tiles the wheel touches now (Gymnasium's w.tiles set, as a count)
  };

  // Totals over the hull, the wheels and the payload.
  struct MassData {
    double total_mass = 0;  // kg: hull + 4 wheels + payload
    double rigid_mass = 0;  // kg: hull + payload (the welded part)
    b2Vec2 rigid_center;    // hull-local centre of mass of hull + payload
  };

  // Creates the hull, then the wheels FL, FR, RL, RR each with its joint, as Gymnasium does:
  // the wheels at (init_x, init_y) + their hull offsets NOT rotated by init_angle (the joints
  // pull them into place during the first step).
  Car(b2World& world, double init_angle, double init_x, double init_y);
  Car(const Car&) = delete;
  Car& operator=(const Car&) = delete;

  // Controls, as car_dynamics.py: front wheels' steer target := s (unclipped); rear wheels'
  // gas moves toward clip(g, 0, 1), rising by at most 0.1 per call; every wheel's brake := b.
  void Steer(double s);
  void Gas(double g);
  void Brake(double b);

  // The wheel model for one time step of `dt` seconds (Car.step): steering servo,
  // engine, brake, tyre forces applied to the wheels. Call before b2World::Step.
  void Step(double dt, const CarParams& params);

  // Makes the payload match `spec`: when it differs from the current one, destroys the old
  // payload body (its weld joint goes with it) and, if spec.mass > 0, creates the new body at
  // the hull-local point, at the hull's angle and with the hull's linear and angular velocity,
  // welded to the hull. Box2D recomputes the bodies' mass data at once; the change acts on the
  // next b2World::Step. REQUIRES: spec.radius >= 0.05 when spec.mass > 0.
  void SetPayload(const PayloadSpec& spec);
  const PayloadSpec& payload_spec() const { return payload_spec_; }

  // Called by the contact listener when wheel `index` starts (+1) or stops (-1) touching a tile.
  void AddWheelTileContact(int index, int delta) { wheels_[index].tiles += delta; }

  const b2Body* hull() const { return hull_; }
  const b2Body* payload() const { return payload_; }  // nullptr without payload
  const std::array<Wheel, 4>& wheels() const { return wheels_; }
  MassData GetMassData() const;

 private:
  b2World& world_;
  b2Body* hull_ = nullptr;
  b2Body* payload_ = nullptr;
  PayloadSpec payload_spec_;  // mass 0: none
  std::array<Wheel, 4> wheels_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_CAR_DYNAMICS_H_
