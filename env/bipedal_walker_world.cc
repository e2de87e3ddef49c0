// Copyright 2026 The DCS Authors.
#include "env/bipedal_walker_world.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace dcs::env {
namespace {

constexpr int kVelocityIterations = 6 * 30;
constexpr int kPositionIterations = 2 * 30;
constexpr uint16 kWalkerCategory = 0x0020;
constexpr uint16 kGroundCategory = 0x0001;

// HULL_POLY in pixels; divided by the scale.
constexpr std::array<std::array<double, 2>, 5> kHullPolygon = {
    {{-30, +9}, {+6, +9}, {+34, +1}, {+34, -8}, {-30, -8}}};

// numpy.sign: -1, 0 or +1.
double Sign(double x) { return static_cast<double>((x > 0) - (x < 0)); }

b2Vec2 Vec(double x, double y) { return b2Vec2(static_cast<float>(x), static_cast<float>(y)); }

// sin and cos of the lidar angles 1.5 i / 10, computed once.
struct LidarDirections {
  LidarDirections() {
    for (int i = 0; i < WalkerWorld::kNumLidar; ++i) {
      sin[i] = std::sin(1.5 * i / 10.0);
      cos[i] = std::cos(1.5 * i / 10.0);
    }
  }
  std::array<double, WalkerWorld::kNumLidar> sin;
  std::array<double, WalkerWorld::kNumLidar> cos;
};

const LidarDirections& Directions() {
  static const LidarDirections directions;
  return directions;
}

b2AABB SegmentBox(const b2Vec2& a, const b2Vec2& b) { return {b2Min(a, b), b2Max(a, b)}; }

}  // namespace

bool WalkerWorld::LidarCandidateCollector::QueryCallback(int32 proxy_id) {
  const auto* proxy = static_cast<const b2FixtureProxy*>(broad_phase->GetUserData(proxy_id));
  if ((proxy->fixture->GetFilterData().categoryBits & 1) != 0) {
    candidates->push_back({proxy->fixture, proxy->childIndex, broad_phase->GetFatAABB(proxy_id)});
  }
  return true;  // keep querying
}

WalkerWorld::WalkerWorld() : world_(std::make_unique<b2World>(b2Vec2(0.0f, -10.0f))) {
  world_->SetContactListener(this);
}

WalkerWorld::~WalkerWorld() { world_->SetContactListener(nullptr); }

void WalkerWorld::BeginContact(b2Contact* contact) {
  const b2Body* a = contact->GetFixtureA()->GetBody();
  const b2Body* b = contact->GetFixtureB()->GetBody();
  if (a == hull_ || b == hull_) game_over_ = true;
  if (a == legs_[1] || b == legs_[1]) ground_contact_[0] = true;
  if (a == legs_[3] || b == legs_[3]) ground_contact_[1] = true;
}

void WalkerWorld::EndContact(b2Contact* contact) {
  const b2Body* a = contact->GetFixtureA()->GetBody();
  const b2Body* b = contact->GetFixtureB()->GetBody();
  if (a == legs_[1] || b == legs_[1]) ground_contact_[0] = false;
  if (a == legs_[3] || b == legs_[3]) ground_contact_[1] = false;
}

void WalkerWorld::Destroy() {
  world_->SetContactListener(nullptr);
  if (ground_ != nullptr) world_->DestroyBody(ground_);
  ground_ = nullptr;
  if (hull_ != nullptr) world_->DestroyBody(hull_);
  hull_ = nullptr;
  payload_ = nullptr;
  for (b2Body*& leg : legs_) {
    if (leg != nullptr) world_->DestroyBody(leg);  // also destroys the joints
    leg = nullptr;
  }
  joints_ = {};
  world_->SetContactListener(this);
}

void WalkerWorld::Build(const WalkerGeometry& geometry, double friction, double motors_torque,
                        Random& random) {
  Destroy();
  geometry_ = geometry;
  game_over_ = false;
  ground_contact_ = {false, false};
  GenerateTerrain(friction, random);
  GenerateClouds(random);
  CreateWalker(motors_torque, random);
}

void WalkerWorld::AddObstacle(const std::array<b2Vec2, 4>& vertices, double friction) {
  b2PolygonShape shape;
  shape.Set(vertices.data(), static_cast<int32>(vertices.size()));
  b2FixtureDef fixture;
  fixture.shape = &shape;
  fixture.friction = static_cast<float>(friction);
  ground_->CreateFixture(&fixture);
  obstacles_.push_back({vertices});
}

// BipedalWalker._generate_terrain, statement by statement, with CARL's
// features in place of the module constants.
void WalkerWorld::GenerateTerrain(double friction, Random& random) {
  enum State : int64_t { kGrass, kStump, kStairs, kPit, kNumStates };
  const WalkerGeometry& g = geometry_;
  const double step = g.terrain_step;
  int64_t state = kGrass;
  double velocity = 0.0;
  double y = g.terrain_height;
  double counter = g.terrain_startpad;  // a float in Python until the first integers() draw
  bool oneshot = false;
  int64_t stair_steps = 0;
  int64_t stair_width = 0;
  int64_t stair_height = 0;
  double original_y = 0;
  terrain_x_.clear();
  terrain_y_.clear();
  obstacles_.clear();
  b2BodyDef ground;  // static, at the origin
  ground_ = world_->CreateBody(&ground);
  for (int i = 0; i < g.terrain_length; ++i) {
    const double x = i * step;
    terrain_x_.push_back(x);
    if (state == kGrass && !oneshot) {
      velocity = 0.8 * velocity + 0.01 * Sign(g.terrain_height - y);
      if (i > g.terrain_startpad) velocity += random.Uniform(-1, 1) / g.scale;
      y += velocity;
    } else if (state == kPit && oneshot) {
      counter = static_cast<double>(random.Integers(3, 5));
      const std::array<b2Vec2, 4> poly = {Vec(x, y), Vec(x + step, y), Vec(x + step, y - 4 * step),
                                          Vec(x, y - 4 * step)};
      AddObstacle(poly, friction);
      const double shift = step * counter;
      AddObstacle({Vec(x + shift, y), Vec(x + step + shift, y), Vec(x + step + shift, y - 4 * step),
                   Vec(x + shift, y - 4 * step)},
                  friction);
      counter += 2;
      original_y = y;
    } else if (state == kPit && !oneshot) {
      y = original_y;
      if (counter > 1) y -= 4 * step;
    } else if (state == kStump && oneshot) {
      counter = static_cast<double>(random.Integers(1, 3));
      const double size = counter * step;
      AddObstacle({Vec(x, y), Vec(x + size, y), Vec(x + size, y + size), Vec(x, y + size)},
                  friction);
    } else if (state == kStairs && oneshot) {
      stair_height = random.Uniform01() > 0.5 ? 1 : -1;
      stair_width = random.Integers(4, 5);  // always 4, and no draw
      stair_steps = random.Integers(3, 5);
      original_y = y;
      for (int64_t s = 0; s < stair_steps; ++s) {
        const double x0 = x + static_cast<double>(s * stair_width) * step;
        const double x1 = x + static_cast<double>((1 + s) * stair_width) * step;
        const double y0 = y + static_cast<double>(s * stair_height) * step;
        const double y1 = y + static_cast<double>(-1 + s * stair_height) * step;
        AddObstacle({Vec(x0, y0), Vec(x1, y0), Vec(x1, y1), Vec(x0, y1)}, friction);
      }
      counter = static_cast<double>(stair_steps * stair_width);
    } else if (state == kStairs && !oneshot) {
      const double s = static_cast<double>(stair_steps * stair_width) - counter -
                       static_cast<double>(stair_height);
      const double n = s / static_cast<double>(stair_width);
      y = original_y + (n * static_cast<double>(stair_height)) * step;
    }
    oneshot = false;
    terrain_y_.push_back(y);
    counter -= 1;
    if (counter == 0) {
      // numpy's integers(grass / 2, grass) truncates the float bound grass / 2.
      counter = static_cast<double>(random.Integers(g.terrain_grass / 2, g.terrain_grass));
      state = state == kGrass && g.hardcore ? random.Integers(1, kNumStates) : kGrass;
      oneshot = true;
    }
  }

  b2EdgeShape edge;
  b2FixtureDef fixture;
  fixture.shape = &edge;
  fixture.friction = static_cast<float>(friction);
  fixture.filter.categoryBits = kGroundCategory;
  for (int i = 0; i + 1 < g.terrain_length; ++i) {
    edge.SetTwoSided(Vec(terrain_x_[i], terrain_y_[i]), Vec(terrain_x_[i + 1], terrain_y_[i + 1]));
    ground_->CreateFixture(&fixture);
  }
}

// BipedalWalker._generate_clouds: render only, but its draws come before the push's.
void WalkerWorld::GenerateClouds(Random& random) {
  const WalkerGeometry& g = geometry_;
  const double step = g.terrain_step;
  clouds_.clear();
  for (int c = 0; c < g.terrain_length / 20; ++c) {
    const double x = random.Uniform(0, g.terrain_length) * step;
    const double y = g.viewport_h / g.scale * 3 / 4;
    Cloud cloud;
    for (int a = 0; a < 5; ++a) {
      const double px = x + 15 * step * std::sin(3.14 * 2 * a / 5) + random.Uniform(0, 5 * step);
      const double py = y + 5 * step * std::cos(3.14 * 2 * a / 5) + random.Uniform(0, 5 * step);
      cloud.vertices[a] = Vec(px, py);
      cloud.x1 = a == 0 ? px : std::min(cloud.x1, px);
      cloud.x2 = a == 0 ? px : std::max(cloud.x2, px);
    }
    clouds_.push_back(cloud);
  }
}

void WalkerWorld::CreateWalker(double motors_torque, Random& random) {
  const WalkerGeometry& g = geometry_;
  const double init_x = g.terrain_step * g.terrain_startpad / 2;
  const double init_y = g.terrain_height + 2 * g.leg_h;

  b2BodyDef body;
  body.type = b2_dynamicBody;
  body.position = Vec(init_x, init_y);
  hull_ = world_->CreateBody(&body);
  std::array<b2Vec2, kHullPolygon.size()> hull_vertices;
  for (size_t i = 0; i < kHullPolygon.size(); ++i) {
    hull_vertices[i] = Vec(kHullPolygon[i][0] / g.scale, kHullPolygon[i][1] / g.scale);
  }
  b2PolygonShape hull_shape;
  hull_shape.Set(hull_vertices.data(), static_cast<int32>(hull_vertices.size()));
  b2FixtureDef hull_fixture;
  hull_fixture.shape = &hull_shape;
  hull_fixture.density = 5.0f;
  hull_fixture.friction = 0.1f;
  hull_fixture.restitution = 0.0f;
  hull_fixture.filter.categoryBits = kWalkerCategory;
  hull_fixture.filter.maskBits = kGroundCategory;
  hull_->CreateFixture(&hull_fixture);
  hull_->ApplyForceToCenter(Vec(random.Uniform(-g.initial_random, g.initial_random), 0), true);

  b2PolygonShape upper_shape;
  upper_shape.SetAsBox(static_cast<float>(g.leg_w / 2), static_cast<float>(g.leg_h / 2));
  b2PolygonShape lower_shape;
  lower_shape.SetAsBox(static_cast<float>(0.8 * g.leg_w / 2), static_cast<float>(g.leg_h / 2));
  b2FixtureDef leg_fixture;  // friction 0.2, Box2D's default
  leg_fixture.density = 1.0f;
  leg_fixture.restitution = 0.0f;
  leg_fixture.filter.categoryBits = kWalkerCategory;
  leg_fixture.filter.maskBits = kGroundCategory;

  int index = 0;
  for (const int side : {-1, +1}) {
    body.angle = static_cast<float>(side * 0.05);
    body.position = Vec(init_x, init_y - g.leg_h / 2 - g.leg_down);
    b2Body* upper = world_->CreateBody(&body);
    leg_fixture.shape = &upper_shape;
    upper->CreateFixture(&leg_fixture);
    b2RevoluteJointDef hip;
    hip.bodyA = hull_;
    hip.bodyB = upper;
    hip.localAnchorA = Vec(0, g.leg_down);
    hip.localAnchorB = Vec(0, g.leg_h / 2);
    // pybox2d sets bodyB.angle - bodyA.angle when both bodies are given.
    hip.referenceAngle = upper->GetAngle() - hull_->GetAngle();
    hip.enableMotor = true;
    hip.enableLimit = true;
    hip.maxMotorTorque = static_cast<float>(motors_torque);
    hip.motorSpeed = static_cast<float>(side);
    hip.lowerAngle = -0.8f;
    hip.upperAngle = 1.1f;
    legs_[index] = upper;
    joints_[index] = static_cast<b2RevoluteJoint*>(world_->CreateJoint(&hip));
    ++index;

    body.position = Vec(init_x, init_y - g.leg_h * 3 / 2 - g.leg_down);
    b2Body* lower = world_->CreateBody(&body);
    leg_fixture.shape = &lower_shape;
    lower->CreateFixture(&leg_fixture);
    b2RevoluteJointDef knee;
    knee.bodyA = upper;
    knee.bodyB = lower;
    knee.localAnchorA = Vec(0, -g.leg_h / 2);
    knee.localAnchorB = Vec(0, g.leg_h / 2);
    knee.referenceAngle = lower->GetAngle() - upper->GetAngle();  // 0
    knee.enableMotor = true;
    knee.enableLimit = true;
    knee.maxMotorTorque = static_cast<float>(motors_torque);
    knee.motorSpeed = 1.0f;
    knee.lowerAngle = -1.6f;
    knee.upperAngle = -0.1f;
    legs_[index] = lower;
    joints_[index] = static_cast<b2RevoluteJoint*>(world_->CreateJoint(&knee));
    ++index;
  }
}

void WalkerWorld::SetGravity(double x, double y) { world_->SetGravity(Vec(x, y)); }

void WalkerWorld::SetTerrainFriction(double friction) {
  if (ground_ == nullptr) return;
  for (b2Fixture* f = ground_->GetFixtureList(); f != nullptr; f = f->GetNext()) {
    f->SetFriction(static_cast<float>(friction));
  }
  // A contact mixes its friction when it is created; re-mix the existing ones.
  for (b2Contact* c = world_->GetContactList(); c != nullptr; c = c->GetNext()) {
    c->ResetFriction();
  }
}

void WalkerWorld::SetPayload(const WalkerPayload& payload) {
  assert(hull_ != nullptr);
  if (payload_ != nullptr) {
    hull_->DestroyFixture(payload_);  // also destroys its contacts
    payload_ = nullptr;
  }
  if (payload.mass > 0 && payload.radius > 0) {
    b2CircleShape circle;
    circle.m_p = Vec(payload.com_x, 0);
    circle.m_radius = static_cast<float>(payload.radius);
    b2FixtureDef fixture;  // default filter: category 0x0001, mask 0xFFFF
    fixture.shape = &circle;
    fixture.density =
        static_cast<float>(payload.mass / (std::numbers::pi * payload.radius * payload.radius));
    fixture.friction = 0.0f;
    fixture.restitution = 0.0f;
    payload_ = hull_->CreateFixture(&fixture);
  }
  hull_->ResetMassData();
}

void WalkerWorld::SetMotors(std::span<const float, 4> action, double speed_hip, double speed_knee,
                            double motors_torque) {
  for (int j = 0; j < kNumLegs; ++j) {
    const double a = action[j];
    const double speed = j % 2 == 0 ? speed_hip : speed_knee;
    joints_[j]->SetMotorSpeed(static_cast<float>(speed * Sign(a)));
    joints_[j]->SetMaxMotorTorque(
        static_cast<float>(motors_torque * std::clamp(std::abs(a), 0.0, 1.0)));
  }
  // pybox2d 2.3's setters wake both bodies every call; 2.4.1's only on a change.
  if (!hull_->IsAwake()) hull_->SetAwake(true);
  for (b2Body* leg : legs_) {
    if (!leg->IsAwake()) leg->SetAwake(true);
  }
}

void WalkerWorld::Step(double dt) {
  world_->Step(static_cast<float>(dt), kVelocityIterations, kPositionIterations);
}

void WalkerWorld::CastLidar(double range, std::span<float, kNumLidar> fractions) {
  const LidarDirections& directions = Directions();
  const b2Vec2 p1 = hull_->GetPosition();
  b2AABB fan = SegmentBox(p1, p1);  // the box of all rays
  for (int i = 0; i < kNumLidar; ++i) {
    lidar_[i] = {.p1 = p1,
                 .p2 = Vec(p1.x + directions.sin[i] * range, p1.y - directions.cos[i] * range),
                 .fraction = 1.0f};
    fan.Combine(SegmentBox(p1, lidar_[i].p2));
  }
  const b2BroadPhase& broad_phase = world_->GetContactManager().m_broadPhase;
  lidar_candidates_.clear();
  LidarCandidateCollector collector{&broad_phase, &lidar_candidates_};
  broad_phase.Query(&collector, fan);

  for (int i = 0; i < kNumLidar; ++i) {
    LidarRay& ray = lidar_[i];
    b2RayCastInput input;  // what b2World::RayCast(callback, p1, p2) passes on
    input.p1 = ray.p1;
    input.p2 = ray.p2;
    input.maxFraction = 1.0f;
    b2AABB reach = SegmentBox(ray.p1, ray.p2);  // the ray clipped at the nearest hit so far
    for (const LidarCandidate& candidate : lidar_candidates_) {
      b2RayCastOutput output;
      if (!b2TestOverlap(candidate.fat_aabb, reach) ||
          !candidate.fixture->RayCast(&output, input, candidate.child_index)) {
        continue;
      }
      input.maxFraction = output.fraction;
      ray.fraction = output.fraction;
      ray.p2 = (1.0f - output.fraction) * input.p1 + output.fraction * input.p2;
      reach = SegmentBox(ray.p1, ray.p2);
    }
    fractions[i] = ray.fraction;
  }
}

}  // namespace dcs::env
