// Copyright 2026 The DCS Authors.
#include "env/car_dynamics.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace dcs::env {
namespace {

// Car drawing coordinates (pixels; times kCarSize gives world units).
constexpr double kHullPoly1[][2] = {{-60, +130}, {+60, +130}, {+60, +110}, {-60, +110}};
constexpr double kHullPoly2[][2] = {{-15, +120}, {+15, +120}, {+20, +20}, {-20, +20}};
constexpr double kHullPoly3[][2] = {{+25, +20}, {+50, -10}, {+50, -40}, {+20, -90},
                                    {-20, -90}, {-50, -40}, {-50, -10}, {-25, +20}};
constexpr double kHullPoly4[][2] = {{-50, -120}, {+50, -120}, {+50, -90}, {-50, -90}};
constexpr double kWheelPos[4][2] = {{-55, +80}, {+55, +80}, {-55, -82}, {+55, -82}};
constexpr double kWheelR = 27;
constexpr double kWheelW = 14;

constexpr int kPayloadSides = 16;
constexpr int kPayloadPieces = 4;  // Box2D 2.4.1 polygons have at most 8 vertices

double Sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

template <size_t N>
void AddHullFixture(b2Body* hull, const double (&poly)[N][2]) {
  b2Vec2 vertices[N];
  for (size_t i = 0; i < N; ++i) {
    vertices[i].Set(static_cast<float>(poly[i][0] * kCarSize),
                    static_cast<float>(poly[i][1] * kCarSize));
  }
  b2PolygonShape shape;
  shape.Set(vertices, static_cast<int32>(N));
  b2FixtureDef fixture;
  fixture.shape = &shape;
  fixture.density = 1.0f;
  hull->CreateFixture(&fixture);
}

}  // namespace

Car::Car(b2World& world, double init_angle, double init_x, double init_y) : world_(world) {
  b2BodyDef hull_def;
  hull_def.type = b2_dynamicBody;
  hull_def.position.Set(static_cast<float>(init_x), static_cast<float>(init_y));
  hull_def.angle = static_cast<float>(init_angle);
  hull_ = world_.CreateBody(&hull_def);
  AddHullFixture(hull_, kHullPoly1);
  AddHullFixture(hull_, kHullPoly2);
  AddHullFixture(hull_, kHullPoly3);
  AddHullFixture(hull_, kHullPoly4);

  const b2Vec2 wheel_poly[4] = {
      {static_cast<float>(-kWheelW * kCarSize), static_cast<float>(+kWheelR * kCarSize)},
      {static_cast<float>(+kWheelW * kCarSize), static_cast<float>(+kWheelR * kCarSize)},
      {static_cast<float>(+kWheelW * kCarSize), static_cast<float>(-kWheelR * kCarSize)},
      {static_cast<float>(-kWheelW * kCarSize), static_cast<float>(-kWheelR * kCarSize)}};
  for (int i = 0; i < 4; ++i) {
    const double wx = kWheelPos[i][0];
    const double wy = kWheelPos[i][1];
    b2BodyDef wheel_def;
    wheel_def.type = b2_dynamicBody;
    wheel_def.position.Set(static_cast<float>(init_x + wx * kCarSize),
                           static_cast<float>(init_y + wy * kCarSize));
    wheel_def.angle = static_cast<float>(init_angle);
    b2Body* body = world_.CreateBody(&wheel_def);
    b2PolygonShape shape;
    shape.Set(wheel_poly, 4);
    b2FixtureDef fixture;
    fixture.shape = &shape;
    fixture.density = 0.1f;
    fixture.filter.categoryBits = 0x0020;
    fixture.filter.maskBits = 0x001;
    fixture.restitution = 0.0f;
    fixture.userData.pointer = CarRacingFixtureTag(CarRacingFixtureKind::kWheel, i);
    body->CreateFixture(&fixture);

    b2RevoluteJointDef joint_def;
    joint_def.bodyA = hull_;
    joint_def.bodyB = body;
    joint_def.localAnchorA.Set(static_cast<float>(wx * kCarSize),
                               static_cast<float>(wy * kCarSize));
    joint_def.localAnchorB.Set(0, 0);
    joint_def.referenceAngle = 0;  // pybox2d would compute it; equal angles make it 0
    joint_def.enableMotor = true;
    joint_def.enableLimit = true;
    joint_def.maxMotorTorque = static_cast<float>(180 * 900 * kCarSize * kCarSize);
    joint_def.motorSpeed = 0;
    joint_def.lowerAngle = -0.4f;
    joint_def.upperAngle = +0.4f;
    wheels_[i].body = body;
    wheels_[i].joint = static_cast<b2RevoluteJoint*>(world_.CreateJoint(&joint_def));
  }
}

void Car::Steer(double s) {
  wheels_[0].steer = s;
  wheels_[1].steer = s;
}

void Car::Gas(double g) {
  g = std::clamp(g, 0.0, 1.0);
  for (int i = 2; i < 4; ++i) {
    double diff = g - wheels_[i].gas;
    if (diff > 0.1) diff = 0.1;  // gradually increase, but stop immediately
    wheels_[i].gas += diff;
  }
}

void Car::Brake(double b) {
  for (Wheel& w : wheels_) w.brake = b;
}

void Car::Step(double dt, const CarParams& params) {
  const double side_gain = 205000 * kCarSize * kCarSize;  // 82
  for (Wheel& w : wheels_) {
    // Steering servo.
    const double joint_angle = w.joint->GetJointAngle();
    const double dir = Sign(w.steer - joint_angle);
    const double val = std::abs(w.steer - joint_angle);
    w.joint->SetMotorSpeed(static_cast<float>(dir * std::min(50.0 * val, 3.0)));

    // Road or grass.
    double friction_limit = params.friction_limit * kCarGrassFrictionFactor;
    if (w.tiles > 0) {
      friction_limit = std::max(friction_limit, params.friction_limit * 1.0);  // road_friction
    }

    const b2Vec2 forw_f = w.body->GetWorldVector(b2Vec2(0, 1));
    const b2Vec2 side_f = w.body->GetWorldVector(b2Vec2(1, 0));
    const b2Vec2 v_f = w.body->GetLinearVelocity();
    const double forw[2] = {forw_f.x, forw_f.y};
    const double side[2] = {side_f.x, side_f.y};
    const double v[2] = {v_f.x, v_f.y};
    const double vf = forw[0] * v[0] + forw[1] * v[1];  // forward speed
    const double vs = side[0] * v[0] + side[1] * v[1];  // side speed

    // Engine: constant power, a small constant keeps it finite at rest.
    w.omega += dt * params.engine_power * w.gas / params.wheel_moment_of_inertia /
               (std::abs(w.omega) + 5.0);

    if (w.brake >= 0.9) {
      w.omega = 0;
    } else if (w.brake > 0) {
      const double brake_dir = -Sign(w.omega);
      double brake_val = params.brake_force * w.brake;
      if (std::abs(brake_val) > std::abs(w.omega)) brake_val = std::abs(w.omega);
      w.omega += brake_dir * brake_val;
    }
    w.phase += w.omega * dt;

    const double vr = w.omega * kCarWheelRadius;  // rim speed
    double f_force = -vf + vr;
    double p_force = -vs;
    f_force *= side_gain;
    p_force *= side_gain;
    const double force = std::sqrt(f_force * f_force + p_force * p_force);
    if (std::abs(force) > friction_limit) {
      f_force /= force;
      p_force /= force;
      f_force *= friction_limit;
      p_force *= friction_limit;
    }
    w.omega -= dt * f_force * kCarWheelRadius / params.wheel_moment_of_inertia;

    w.body->ApplyForceToCenter(b2Vec2(static_cast<float>(p_force * side[0] + f_force * forw[0]),
                                      static_cast<float>(p_force * side[1] + f_force * forw[1])),
                               true);
  }
}

void Car::SetPayload(const PayloadSpec& spec) {
  const bool had = payload_ != nullptr;
  const bool wants = spec.mass > 0 && spec.radius > 0;
  if (spec == payload_spec_ && had == wants) return;
  if (payload_ != nullptr) {
    world_.DestroyBody(payload_);  // destroys the weld joint too
    payload_ = nullptr;
  }
  payload_spec_ = spec;
  if (!wants) return;
  assert(spec.radius >= 0.05);

  b2BodyDef def;
  def.type = b2_dynamicBody;
  def.position =
      hull_->GetWorldPoint(b2Vec2(static_cast<float>(spec.x), static_cast<float>(spec.y)));
  def.angle = hull_->GetAngle();
  payload_ = world_.CreateBody(&def);

  // The 16-gon as four convex sectors (centre plus five rim vertices each).
  constexpr double kPi = std::numbers::pi;
  const double area =
      0.5 * kPayloadSides * spec.radius * spec.radius * std::sin(2 * kPi / kPayloadSides);
  b2FixtureDef fixture;
  fixture.density = static_cast<float>(spec.mass / area);
  fixture.friction = 0.0f;
  fixture.restitution = 0.0f;
  constexpr int kPerPiece = kPayloadSides / kPayloadPieces;
  for (int piece = 0; piece < kPayloadPieces; ++piece) {
    b2Vec2 vertices[kPerPiece + 2];
    vertices[0].Set(0, 0);
    for (int k = 0; k <= kPerPiece; ++k) {
      const double a = 2 * kPi * (piece * kPerPiece + k) / kPayloadSides;
      vertices[k + 1].Set(static_cast<float>(spec.radius * std::cos(a)),
                          static_cast<float>(spec.radius * std::sin(a)));
    }
    b2PolygonShape shape;
    shape.Set(vertices, kPerPiece + 2);
    fixture.shape = &shape;
    payload_->CreateFixture(&fixture);
  }
  payload_->SetLinearVelocity(hull_->GetLinearVelocity());
  payload_->SetAngularVelocity(hull_->GetAngularVelocity());

  b2WeldJointDef weld;
  weld.bodyA = hull_;
  weld.bodyB = payload_;
  weld.localAnchorA.Set(static_cast<float>(spec.x), static_cast<float>(spec.y));
  weld.localAnchorB.Set(0, 0);
  weld.referenceAngle = 0;
  world_.CreateJoint(&weld);
}

Car::MassData Car::GetMassData() const {
  MassData data;
  const b2Vec2 hull_center = hull_->GetLocalCenter();
  double mx = hull_->GetMass() * hull_center.x;
  double my = hull_->GetMass() * hull_center.y;
  data.rigid_mass = hull_->GetMass();
  if (payload_ != nullptr) {
    const b2Vec2 c = hull_->GetLocalPoint(payload_->GetWorldCenter());
    mx += payload_->GetMass() * c.x;
    my += payload_->GetMass() * c.y;
    data.rigid_mass += payload_->GetMass();
  }
  data.rigid_center.Set(static_cast<float>(mx / data.rigid_mass),
                        static_cast<float>(my / data.rigid_mass));
  data.total_mass = data.rigid_mass;
  for (const Wheel& w : wheels_) data.total_mass += w.body->GetMass();
  return data;
}

}  // namespace dcs::env
