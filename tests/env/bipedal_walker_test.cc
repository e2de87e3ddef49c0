// Copyright 2026 The DCS Authors.
#include "env/bipedal_walker.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "env/bipedal_walker_heuristic.h"
#include "env/dynamic_context_env.h"
#include "env/raster.h"
#include "env/schedule_config.h"
#include "env/vector_env.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using ::testing::HasSubstr;

using Observation = std::array<float, BipedalWalker::kObservationSize>;
using Action = std::array<float, BipedalWalker::kActionSize>;

constexpr double kTerrainHeight = 400.0 / 30.0 / 4.0;
constexpr double kHullMass = 5.42222;  // Gymnasium 1.4.0's hull polygon at density 5
constexpr double kHullCenterX = -0.020036;
constexpr double kHullCenterY = -0.005647;

b2MassData HullMass(const BipedalWalker& env) {
  b2MassData mass;
  env.world().hull()->GetMassData(&mass);
  return mass;
}

// A walker without payload unless a test asks for one.
BipedalWalker Walker(double payload_mass = 0.0) {
  BipedalWalker env;
  env.SetFeature(BipedalWalker::kPayloadMass, payload_mass);
  return env;
}

struct Episode {
  double total_reward = 0;
  int steps = 0;
  bool fell = false;         // ended with -100
  bool reached_end = false;  // terminated without -100
  bool truncated = false;
  double distance = 0;     // hull x travelled, m
  double final_angle = 0;  // hull angle at the end, rad
};

// Gymnasium's heuristic driver (bipedal_walker.py's __main__): a zero action first, then the gait.
Episode RunEpisode(BipedalWalker& env, uint64_t seed) {
  Random random(seed);
  Observation observation;
  env.Reset(random, observation);
  const double start_x = env.world().hull()->GetPosition().x;
  WalkerHeuristic gait;
  Action action = {0, 0, 0, 0};
  Episode episode;
  while (true) {
    const StepResult result = env.Step(action, observation);
    episode.total_reward += result.reward;
    ++episode.steps;
    if (result.done()) {
      episode.fell = result.terminated && result.reward == -100;
      episode.reached_end = result.terminated && result.reward != -100;
      episode.truncated = result.truncated;
      break;
    }
    action = gait.Act(observation);
  }
  episode.distance = env.world().hull()->GetPosition().x - start_x;
  episode.final_angle = env.world().hull()->GetAngle();
  return episode;
}

struct Summary {
  double mean = 0;
  double stddev = 0;
  int moved_forward = 0;  // more than 5 m
  int reached_end = 0;
  int truncated = 0;
  int fell_forward = 0;  // fell with the nose down
  int fell_backward = 0;
};

Summary RunHeuristic(BipedalWalker& env, int seeds) {
  Summary summary;
  double sum = 0;
  double sum_sq = 0;
  for (int seed = 0; seed < seeds; ++seed) {
    const Episode e = RunEpisode(env, seed);
    sum += e.total_reward;
    sum_sq += e.total_reward * e.total_reward;
    summary.moved_forward += e.distance > 5;
    summary.reached_end += e.reached_end;
    summary.truncated += e.truncated;
    summary.fell_forward += e.fell && e.final_angle < 0;
    summary.fell_backward += e.fell && e.final_angle > 0;
  }
  summary.mean = sum / seeds;
  summary.stddev = std::sqrt(std::max(0.0, sum_sq / seeds - summary.mean * summary.mean));
  return summary;
}

TEST(BipedalWalkerTest, DeclaresTheEnvironmentShape) {
  EXPECT_EQ(BipedalWalker::kName, "bipedal_walker");
  EXPECT_EQ(BipedalWalker::kObservationSize, 24);
  EXPECT_EQ(BipedalWalker::kActionSize, 4);
  EXPECT_EQ(BipedalWalker::kMaxEpisodeSteps, 1600);
  EXPECT_EQ(BipedalWalker::Features().size(), BipedalWalker::kNumFeatures);
  EXPECT_EQ(BipedalWalker::Features().feature(BipedalWalker::kGravityY).name, "GRAVITY_Y");
  EXPECT_EQ(BipedalWalker::Features().feature(BipedalWalker::kTerrainStartpad).name,
            "TERRAIN_STARTPAD");
  EXPECT_EQ(BipedalWalker::Features().feature(BipedalWalker::kComX).name, "COM_X");
  EXPECT_DOUBLE_EQ(BipedalWalker::Features().feature(BipedalWalker::kTerrainHeight).default_value,
                   kTerrainHeight);
  EXPECT_EQ(BipedalWalker::Features().feature(BipedalWalker::kPayloadMass).default_value, 2.0);
  EXPECT_EQ(BipedalWalker::Features().feature(BipedalWalker::kPayloadRadius).default_value, 0.5);
}

TEST(BipedalWalkerTest, ValidatesContexts) {
  std::vector<double> context = BipedalWalker::Features().Defaults();
  EXPECT_TRUE(BipedalWalker::ValidateContext(context).ok());
  for (const double com_x : {-1.7, 1.7, -2.0, 2.0}) {  // the paper's evaluation grid fits
    context[BipedalWalker::kComX] = com_x;
    EXPECT_TRUE(BipedalWalker::ValidateContext(context).ok()) << com_x;
  }
  context[BipedalWalker::kComX] = 2.5;
  EXPECT_THAT(BipedalWalker::ValidateContext(context).message(), HasSubstr("COM_X"));
  context[BipedalWalker::kComX] = 0;
  context[BipedalWalker::kTerrainLength] = 150.5;
  EXPECT_THAT(BipedalWalker::ValidateContext(context).message(), HasSubstr("integer"));
  context[BipedalWalker::kTerrainLength] = 200;
  context[BipedalWalker::kGravityY] = 1.0;
  EXPECT_FALSE(BipedalWalker::ValidateContext(context).ok());
}

TEST(BipedalWalkerTest, BodiesHaveTheSpecifiedMassProperties) {
  BipedalWalker env = Walker();
  Random random(0);
  Observation observation;
  env.Reset(random, observation);
  const b2MassData hull = HullMass(env);
  EXPECT_NEAR(hull.mass, kHullMass, 1e-4);
  EXPECT_NEAR(hull.center.x, kHullCenterX, 1e-5);
  EXPECT_NEAR(hull.center.y, kHullCenterY, 1e-5);
  // b2MassData::I is about the body origin.
  EXPECT_NEAR(hull.I - hull.mass * b2Dot(hull.center, hull.center), 1.99940, 1e-4);
  EXPECT_NEAR(env.world().leg(0)->GetMass(), 0.302222, 1e-5);
  EXPECT_NEAR(env.world().leg(1)->GetMass(), 0.241778, 1e-5);
  EXPECT_NEAR(env.world().leg(2)->GetMass(), 0.302222, 1e-5);
  EXPECT_NEAR(env.world().leg(3)->GetMass(), 0.241778, 1e-5);
  EXPECT_EQ(env.world().payload(), nullptr);
}

TEST(BipedalWalkerTest, JointsAndWorldFollowPybox2dConventions) {
  BipedalWalker env = Walker();
  Random random(0);
  Observation observation;
  env.Reset(random, observation);
  // Hip reference angles are leg angle - hull angle (as pybox2d sets them); knees 0.
  EXPECT_FLOAT_EQ(env.world().joint(0)->GetReferenceAngle(), -0.05f);
  EXPECT_FLOAT_EQ(env.world().joint(2)->GetReferenceAngle(), 0.05f);
  EXPECT_EQ(env.world().joint(1)->GetReferenceAngle(), 0.0f);
  EXPECT_EQ(env.world().joint(3)->GetReferenceAngle(), 0.0f);
  EXPECT_FLOAT_EQ(env.world().joint(0)->GetLowerLimit(), -0.8f);
  EXPECT_FLOAT_EQ(env.world().joint(1)->GetUpperLimit(), -0.1f);
  EXPECT_EQ(env.world().world().GetGravity().x, 0.0f);
  EXPECT_EQ(env.world().world().GetGravity().y, -10.0f);
}

TEST(BipedalWalkerTest, ResetTakesOneInternalZeroActionStep) {
  BipedalWalker env = Walker();
  Random random(1);
  Observation observation;
  env.Reset(random, observation);
  EXPECT_EQ(env.elapsed_steps(), 0);
  // The zero action left every motor at speed 0 and torque 0.
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(env.world().joint(j)->GetMotorSpeed(), 0.0f) << j;
    EXPECT_EQ(env.world().joint(j)->GetMaxMotorTorque(), 0.0f) << j;
  }
  // One step of 1/50 s from (init_x, init_y): gravity gave the hull -10/50 m/s (the joint
  // solver also lifts it while it corrects the initial joint errors).
  const b2Body* hull = env.world().hull();
  EXPECT_NEAR(hull->GetPosition().x, 14.0 / 30.0 * 20 / 2, 0.01);
  EXPECT_NE(hull->GetPosition().y, static_cast<float>(kTerrainHeight + 2 * 34.0 / 30.0));
  EXPECT_NEAR(hull->GetLinearVelocity().y, -10.0 / 50, 0.01);
  EXPECT_EQ(observation[3],
            static_cast<float>(0.3 * hull->GetLinearVelocity().y * (400.0 / 30.0) / 50));
  // Its reward (0) set prev_shaping: the first agent step's reward is a shaping difference.
  const double x0 = hull->GetPosition().x;
  const double angle0 = hull->GetAngle();
  const Action zero = {0, 0, 0, 0};
  const StepResult result = env.Step(zero, observation);
  const double expected = 130 * (static_cast<double>(hull->GetPosition().x) - x0) / 30 -
                          5 * (std::abs(static_cast<double>(hull->GetAngle())) - std::abs(angle0));
  EXPECT_NEAR(result.reward, expected, 1e-9);
  EXPECT_NE(result.reward, 0.0);
}

TEST(BipedalWalkerTest, ObservationLayoutAndScaling) {
  BipedalWalker env = Walker();
  Random random(2);
  Observation observation;
  env.Reset(random, observation);
  const WalkerWorld& world = env.world();
  // Right after reset the walker stands almost still above the flat start pad.
  EXPECT_LT(std::abs(observation[2]), 0.01);
  const double hull_y = world.hull()->GetPosition().y;
  EXPECT_NEAR(observation[14], (hull_y - kTerrainHeight) / (160.0 / 30.0), 1e-5);
  for (int i = 14; i < 24; ++i) {
    EXPECT_GT(observation[i], 0.0f) << i;
    EXPECT_LE(observation[i], 1.0f) << i;
  }

  const Action action = {0.5f, -0.3f, -1.0f, 0.8f};
  for (int t = 0; t < 30; ++t) env.Step(action, observation);
  const b2Body* hull = world.hull();
  EXPECT_EQ(observation[0], hull->GetAngle());
  EXPECT_EQ(observation[1], static_cast<float>(2.0 * hull->GetAngularVelocity() / 50));
  EXPECT_EQ(observation[2], static_cast<float>(0.3 * hull->GetLinearVelocity().x * 20.0 / 50));
  EXPECT_EQ(observation[3],
            static_cast<float>(0.3 * hull->GetLinearVelocity().y * (400.0 / 30.0) / 50));
  for (int side = 0; side < 2; ++side) {
    const b2RevoluteJoint* hip = world.joint(2 * side);
    const b2RevoluteJoint* knee = world.joint(2 * side + 1);
    const int base = 4 + 5 * side;
    EXPECT_EQ(observation[base], hip->GetJointAngle());
    EXPECT_EQ(observation[base + 1], static_cast<float>(hip->GetJointSpeed() / 4.0));
    EXPECT_EQ(observation[base + 2], static_cast<float>(knee->GetJointAngle() + 1.0));
    EXPECT_EQ(observation[base + 3], static_cast<float>(knee->GetJointSpeed() / 6.0));
    EXPECT_EQ(observation[base + 4], world.ground_contact(side) ? 1.0f : 0.0f);
  }
  for (int i = 0; i < 10; ++i) EXPECT_EQ(observation[14 + i], world.lidar(i).fraction);
  // The motors follow Gymnasium's sign/clip rule.
  EXPECT_FLOAT_EQ(world.joint(0)->GetMotorSpeed(), 4.0f);
  EXPECT_FLOAT_EQ(world.joint(0)->GetMaxMotorTorque(), 40.0f);
  EXPECT_FLOAT_EQ(world.joint(1)->GetMotorSpeed(), -6.0f);
  EXPECT_FLOAT_EQ(world.joint(2)->GetMaxMotorTorque(), 80.0f);
}

TEST(BipedalWalkerTest, RewardIsShapingDifferenceMinusTorqueCost) {
  BipedalWalker env = Walker();
  Random random(3);
  Observation observation;
  env.Reset(random, observation);
  const Action action = {0.5f, -2.0f, 0.0f, 0.25f};  // |-2| is clipped to 1
  const b2Body* hull = env.world().hull();
  for (int t = 0; t < 20; ++t) {
    const double x0 = hull->GetPosition().x;
    const double angle0 = hull->GetAngle();
    const StepResult result = env.Step(action, observation);
    ASSERT_FALSE(result.terminated);
    const double shaping0 = 130 * x0 / 30 - 5 * std::abs(angle0);
    const double shaping1 = 130 * static_cast<double>(hull->GetPosition().x) / 30 -
                            5 * std::abs(static_cast<double>(hull->GetAngle()));
    EXPECT_NEAR(result.reward, shaping1 - shaping0 - 0.00035 * 80 * (0.5 + 1 + 0 + 0.25), 1e-9);
  }
}

TEST(BipedalWalkerTest, TerrainStartsFlatAndFollowsTheSeed) {
  BipedalWalker a = Walker();
  BipedalWalker b = Walker();
  Observation observation;
  Random r1(5);
  a.Reset(r1, observation);
  Random r2(5);
  b.Reset(r2, observation);
  const std::span<const double> ya = a.world().terrain_y();
  ASSERT_EQ(ya.size(), 200u);
  for (int i = 0; i <= 20; ++i) EXPECT_EQ(ya[i], kTerrainHeight) << i;
  EXPECT_NE(ya[21], kTerrainHeight);
  for (int i = 0; i < 200; ++i) EXPECT_DOUBLE_EQ(a.world().terrain_x()[i], i * 14.0 / 30.0);
  EXPECT_TRUE(std::ranges::equal(ya, b.world().terrain_y()));
  EXPECT_TRUE(a.world().obstacles().empty());
  EXPECT_EQ(a.world().clouds().size(), 10u);

  Random r3(6);
  b.Reset(r3, observation);
  EXPECT_FALSE(std::ranges::equal(ya, b.world().terrain_y()));
}

// The normal-terrain draws, replayed independently: one integers(5, 10) per grass stretch, one
// uniform(-1, 1) per grass point after the start pad (not on the flat point after a stretch),
// then 10 clouds of 11 draws, then the push. Both generators must end in the same state.
TEST(BipedalWalkerTest, NormalTerrainDrawsInGymnasiumOrder) {
  BipedalWalker env = Walker();
  Observation observation;
  for (const uint64_t seed : {0u, 42u}) {
    Random random(seed);
    env.Reset(random, observation);
    Random replay(seed);
    double y = kTerrainHeight;
    double velocity = 0;
    int counter = 20;
    bool flat = false;
    for (int i = 0; i < 200; ++i) {
      if (!flat) {
        velocity = 0.8 * velocity + 0.01 * ((kTerrainHeight - y > 0) - (kTerrainHeight - y < 0));
        if (i > 20) velocity += replay.Uniform(-1, 1) / 30.0;
        y += velocity;
      }
      flat = false;
      ASSERT_EQ(env.world().terrain_y()[i], y) << "seed " << seed << " point " << i;
      if (--counter == 0) {
        counter = static_cast<int>(replay.Integers(5, 10));
        flat = true;
      }
    }
    for (int draw = 0; draw < 10 * 11; ++draw) replay.Uniform01();
    replay.Uniform(-5, 5);
    EXPECT_EQ(random.Uniform01(), replay.Uniform01()) << "seed " << seed;
  }
}

// Gymnasium's LidarCallback on b2World::RayCast: ignore fixtures whose category bit 0 is clear,
// clip the ray at every other. The last report is the nearest hit.
class GymnasiumLidarCallback final : public b2RayCastCallback {
 public:
  float ReportFixture(b2Fixture* fixture, const b2Vec2& point, const b2Vec2& /*normal*/,
                      float reported_fraction) override {
    if ((fixture->GetFilterData().categoryBits & 1) == 0) return -1;
    hit = fixture;
    p2 = point;
    fraction = reported_fraction;
    return reported_fraction;
  }
  const b2Fixture* hit = nullptr;
  b2Vec2 p2{0, 0};
  float fraction = 1;
};

// CastLidar answers exactly what Gymnasium's per-ray b2World::RayCast answers, on terrain edges,
// hardcore obstacles and a payload placed where the rays can see it.
TEST(BipedalWalkerTest, LidarEqualsGymnasiumsWorldRayCast) {
  BipedalWalker env = Walker(/*payload_mass=*/2.0);
  env.SetFeature(BipedalWalker::kHardcore, 1);
  env.SetFeature(BipedalWalker::kComX, 1.2);  // the payload circle crosses the far rays
  Random random(11);
  Random action_random(12);
  Observation observation;
  std::array<int, b2Shape::e_typeCount> hits_by_shape{};
  for (int episode = 0; episode < 8; ++episode) {
    env.Reset(random, observation);
    for (bool done = false; !done;) {
      Action action;
      for (float& a : action) a = static_cast<float>(action_random.Uniform(-1, 1));
      done = env.Step(action, observation).done();
      const WalkerWorld& world = env.world();
      for (int i = 0; i < WalkerWorld::kNumLidar; ++i) {
        const WalkerWorld::LidarRay& ray = world.lidar(i);
        const double angle = 1.5 * i / 10.0;
        const double range = 160.0 / 30.0;
        const b2Vec2 p1 = world.hull()->GetPosition();
        const b2Vec2 p2(static_cast<float>(p1.x + std::sin(angle) * range),
                        static_cast<float>(p1.y - std::cos(angle) * range));
        GymnasiumLidarCallback reference;
        reference.p2 = p2;
        world.world().RayCast(&reference, p1, p2);
        ASSERT_EQ(ray.fraction, reference.fraction) << "episode " << episode << " ray " << i;
        ASSERT_EQ(ray.p2.x, reference.p2.x) << "episode " << episode << " ray " << i;
        ASSERT_EQ(ray.p2.y, reference.p2.y) << "episode " << episode << " ray " << i;
        ASSERT_EQ(observation[14 + i], reference.fraction);
        if (reference.hit != nullptr) ++hits_by_shape[reference.hit->GetType()];
      }
    }
  }
  EXPECT_GT(hits_by_shape[b2Shape::e_edge], 0);     // terrain
  EXPECT_GT(hits_by_shape[b2Shape::e_polygon], 0);  // obstacles
  EXPECT_GT(hits_by_shape[b2Shape::e_circle], 0);   // the payload
}

TEST(BipedalWalkerTest, HardcoreBuildsObstaclesAndRunsLonger) {
  BipedalWalker env = Walker();
  env.SetFeature(BipedalWalker::kHardcore, 1);
  Random random(7);
  Observation observation;
  env.Reset(random, observation);
  EXPECT_FALSE(env.world().obstacles().empty());
  EXPECT_EQ(env.max_episode_steps(), BipedalWalker::kMaxHardcoreEpisodeSteps);
  for (int i = 0; i <= 20; ++i) EXPECT_EQ(env.world().terrain_y()[i], kTerrainHeight);
  // The terrain is one static body: 199 edges and a polygon per obstacle, all seen by the lidar
  // (category 0x0001).
  int static_bodies = 0;
  int edges = 0;
  int polygons = 0;
  for (const b2Body* body = env.world().world().GetBodyList(); body != nullptr;
       body = body->GetNext()) {
    if (body->GetType() != b2_staticBody) continue;
    ++static_bodies;
    for (const b2Fixture* f = body->GetFixtureList(); f != nullptr; f = f->GetNext()) {
      EXPECT_EQ(f->GetFilterData().categoryBits, 0x0001);
      edges += f->GetType() == b2Shape::e_edge;
      polygons += f->GetType() == b2Shape::e_polygon;
    }
  }
  EXPECT_EQ(static_bodies, 1);
  EXPECT_EQ(edges, 199);
  EXPECT_EQ(polygons, static_cast<int>(env.world().obstacles().size()));

  env.SetFeature(BipedalWalker::kHardcore, 0);
  EXPECT_EQ(env.max_episode_steps(), BipedalWalker::kMaxHardcoreEpisodeSteps);  // until reset
  env.Reset(random, observation);
  EXPECT_TRUE(env.world().obstacles().empty());
  EXPECT_EQ(env.max_episode_steps(), BipedalWalker::kMaxEpisodeSteps);
}

TEST(BipedalWalkerTest, FallingEndsTheEpisodeWithMinus100) {
  BipedalWalker env = Walker();
  Random random(3);
  Observation observation;
  env.Reset(random, observation);
  const Action zero = {0, 0, 0, 0};  // limp motors: the walker collapses onto its hull
  StepResult result;
  int steps = 0;
  while (!result.done() && steps < 1000) {
    result = env.Step(zero, observation);
    ++steps;
  }
  EXPECT_TRUE(result.terminated);
  EXPECT_FALSE(result.truncated);
  EXPECT_EQ(result.reward, -100);
  EXPECT_TRUE(env.world().game_over());
  // Stepping on is allowed and keeps reporting the fall.
  result = env.Step(zero, observation);
  EXPECT_TRUE(result.terminated);
  EXPECT_EQ(result.reward, -100);
  // Reset clears it.
  env.Reset(random, observation);
  EXPECT_FALSE(env.world().game_over());
}

// Holds a stance with the legs apart and the knees straight: a walker that neither falls nor
// moves on (it stands for 1600 steps on seeds 0-9).
Action Stand(const Observation& s) {
  auto pd = [](double target, double angle, double speed) {
    return static_cast<float>(std::clamp(4.0 * (target - angle) - 0.5 * speed, -1.0, 1.0));
  };
  return {pd(0.2, s[4], s[5]), pd(1.0, s[6], s[7]), pd(-0.2, s[9], s[10]), pd(1.0, s[11], s[12])};
}

TEST(BipedalWalkerTest, TruncatesAtTheTimeLimit) {
  BipedalWalker env = Walker();
  Random random(4);
  Observation observation;
  env.Reset(random, observation);
  for (int step = 1; step <= BipedalWalker::kMaxEpisodeSteps; ++step) {
    const StepResult result = env.Step(Stand(observation), observation);
    ASSERT_FALSE(result.terminated) << step;
    ASSERT_EQ(result.truncated, step == BipedalWalker::kMaxEpisodeSteps) << step;
  }
  EXPECT_EQ(env.elapsed_steps(), BipedalWalker::kMaxEpisodeSteps);
  // Standing still: no horizontal speed, head level.
  EXPECT_LT(std::abs(observation[2]), 0.01);
  EXPECT_LT(std::abs(observation[0]), 0.1);
  EXPECT_NEAR(env.world().hull()->GetPosition().x, 14.0 / 30.0 * 20 / 2, 0.1);
}

TEST(BipedalWalkerTest, HeuristicGaitWalks) {
  BipedalWalker env = Walker();
  constexpr int kSeeds = 100;
  const Summary summary = RunHeuristic(env, kSeeds);
  RecordProperty("mean_return", std::to_string(summary.mean));
  RecordProperty("stddev_return", std::to_string(summary.stddev));
  // Gymnasium (Box2D 2.3): 102.6 +- 125.1 over 1000 episodes, so a 100-seed mean has a standard
  // error of about 12.5. This port, seeds 0-99: 125.2 +- 122.2; every episode gets more than
  // 5 m forward, 13 reach the far end, 13 run into the time limit, 74 fall on their nose.
  EXPECT_GT(summary.mean, 102.6 - 40);
  EXPECT_LT(summary.mean, 102.6 + 40);
  EXPECT_GT(summary.stddev, 60);
  EXPECT_GE(summary.moved_forward, 90);
  EXPECT_GE(summary.reached_end + summary.truncated, 5);
}

TEST(BipedalWalkerTest, HeuristicGaitFailsOnHardcoreAsInGymnasium) {
  BipedalWalker env = Walker();
  env.SetFeature(BipedalWalker::kHardcore, 1);
  constexpr int kSeeds = 100;
  const Summary summary = RunHeuristic(env, kSeeds);
  RecordProperty("mean_return_hardcore", std::to_string(summary.mean));
  // Gymnasium: -59.2 +- 25.2 (standard error of a 100-seed mean: about 2.5). This port: -60.9
  // +- 25.8 over seeds 0-99.
  EXPECT_GT(summary.mean, -59.2 - 15);
  EXPECT_LT(summary.mean, -59.2 + 15);
  EXPECT_EQ(summary.reached_end, 0);
}

TEST(BipedalWalkerTest, PayloadChangesHullMassAndCentre) {
  BipedalWalker env = Walker(2.0);
  Random random(0);
  Observation observation;
  env.Reset(random, observation);  // COM_X 0, radius 0.5
  ASSERT_NE(env.world().payload(), nullptr);
  b2MassData mass = HullMass(env);
  EXPECT_NEAR(mass.mass, kHullMass + 2.0, 1e-4);
  EXPECT_NEAR(mass.center.x, kHullMass * kHullCenterX / (kHullMass + 2.0), 1e-5);
  EXPECT_EQ(env.world().payload()->GetFilterData().categoryBits, 0x0001);  // reference filter
  EXPECT_EQ(env.world().payload()->GetShape()->m_radius, 0.5f);

  // COM_X moves at the next step, not before.
  env.SetFeature(BipedalWalker::kComX, 1.0);
  EXPECT_EQ(HullMass(env).center.x, mass.center.x);
  const Action zero = {0, 0, 0, 0};
  env.Step(zero, observation);
  mass = HullMass(env);
  EXPECT_NEAR(mass.mass, kHullMass + 2.0, 1e-4);
  EXPECT_NEAR(mass.center.x, (kHullMass * kHullCenterX + 2.0 * 1.0) / (kHullMass + 2.0), 1e-5);
  const auto* circle = static_cast<const b2CircleShape*>(env.world().payload()->GetShape());
  EXPECT_EQ(circle->m_p.x, 1.0f);
  EXPECT_EQ(circle->m_p.y, 0.0f);

  env.SetFeature(BipedalWalker::kPayloadMass, 5.0);
  env.SetFeature(BipedalWalker::kPayloadRadius, 0.25);
  env.Step(zero, observation);
  EXPECT_NEAR(HullMass(env).mass, kHullMass + 5.0, 1e-4);
  EXPECT_EQ(env.world().payload()->GetShape()->m_radius, 0.25f);

  env.SetFeature(BipedalWalker::kPayloadMass, 0.0);  // removes the payload
  env.Step(zero, observation);
  EXPECT_EQ(env.world().payload(), nullptr);
  EXPECT_NEAR(HullMass(env).mass, kHullMass, 1e-4);
  EXPECT_NEAR(HullMass(env).center.x, kHullCenterX, 1e-5);
}

TEST(BipedalWalkerTest, PayloadPositionChangesTheGait) {
  // The paper's payload (2 kg, 0.5 m) on the hand-tuned gait, which knows nothing of it: the
  // walker tips toward the payload. Figures over seeds 0-99: no payload 125.2, COM_X 0: -74.2,
  // +0.4: -88.5, -0.4: -119.5.
  constexpr int kSeeds = 100;
  BipedalWalker env = Walker(2.0);
  env.SetFeature(BipedalWalker::kComX, 0.0);
  const Summary centre = RunHeuristic(env, kSeeds);
  env.SetFeature(BipedalWalker::kComX, 0.4);
  const Summary front = RunHeuristic(env, kSeeds);
  env.SetFeature(BipedalWalker::kComX, -0.4);
  const Summary back = RunHeuristic(env, kSeeds);
  RecordProperty("mean_return_com_0", std::to_string(centre.mean));
  RecordProperty("mean_return_com_plus_0_4", std::to_string(front.mean));
  RecordProperty("mean_return_com_minus_0_4", std::to_string(back.mean));
  EXPECT_GT(std::abs(front.mean - centre.mean), 5);
  EXPECT_GT(std::abs(back.mean - centre.mean), 5);
  EXPECT_GT(std::abs(front.mean - back.mean), 5);
  // A payload in front tips the walker onto its nose, one behind onto its back.
  EXPECT_GE(front.fell_forward, 90);
  EXPECT_GE(back.fell_backward, 90);
}

// Two walkers on the same seed and actions, one with a feature changed mid-episode.
class TwinWalkers {
 public:
  explicit TwinWalkers(uint64_t seed) {
    Random ra(seed);
    a_.Reset(ra, observation_a_);
    Random rb(seed);
    b_.Reset(rb, observation_b_);
    for (int t = 0; t < 10; ++t) Step({0.3f, -0.2f, -0.3f, 0.2f});
  }
  std::pair<StepResult, StepResult> Step(const Action& action) {
    return {a_.Step(action, observation_a_), b_.Step(action, observation_b_)};
  }
  BipedalWalker& a() { return a_; }
  BipedalWalker& b() { return b_; }

 private:
  BipedalWalker a_ = Walker();
  BipedalWalker b_ = Walker();
  Observation observation_a_;
  Observation observation_b_;
};

TEST(BipedalWalkerTest, GravityChangeActsAtTheNextStep) {
  TwinWalkers twins(8);
  ASSERT_EQ(twins.a().world().hull()->GetLinearVelocity().y,
            twins.b().world().hull()->GetLinearVelocity().y);
  twins.b().SetFeature(BipedalWalker::kGravityY, -20);
  twins.b().SetFeature(BipedalWalker::kGravityX, 5);
  EXPECT_EQ(twins.b().world().world().GetGravity().y, -10.0f);  // not yet
  twins.Step({0, 0, 0, 0});
  EXPECT_EQ(twins.b().world().world().GetGravity().y, -20.0f);
  EXPECT_LT(twins.b().world().hull()->GetLinearVelocity().y,
            twins.a().world().hull()->GetLinearVelocity().y - 0.05);
  EXPECT_GT(twins.b().world().hull()->GetLinearVelocity().x,
            twins.a().world().hull()->GetLinearVelocity().x + 0.02);
}

TEST(BipedalWalkerTest, MotorFeaturesActAtTheNextStep) {
  TwinWalkers twins(9);
  BipedalWalker& env = twins.b();
  env.SetFeature(BipedalWalker::kMotorsTorque, 200);
  env.SetFeature(BipedalWalker::kSpeedHip, 8);
  const b2Body* hull = env.world().hull();
  const double shaping0 = 130 * static_cast<double>(hull->GetPosition().x) / 30 -
                          5 * std::abs(static_cast<double>(hull->GetAngle()));
  const auto [ra, rb] = twins.Step({1, 0, -0.5f, 0});
  EXPECT_FLOAT_EQ(env.world().joint(0)->GetMaxMotorTorque(), 200.0f);
  EXPECT_FLOAT_EQ(env.world().joint(2)->GetMaxMotorTorque(), 100.0f);
  EXPECT_FLOAT_EQ(env.world().joint(0)->GetMotorSpeed(), 8.0f);
  EXPECT_NE(twins.a().world().joint(0)->GetJointSpeed(), env.world().joint(0)->GetJointSpeed());
  // The torque cost scales with MOTORS_TORQUE: 0.00035 * torque per unit |action|.
  const double shaping1 = 130 * static_cast<double>(hull->GetPosition().x) / 30 -
                          5 * std::abs(static_cast<double>(hull->GetAngle()));
  EXPECT_NEAR(rb.reward, shaping1 - shaping0 - 0.00035 * 200 * 1.5, 1e-9);
  // The joint speed observation is scaled by the new SPEED_HIP.
  Observation observation;
  env.Step(Action{0, 0, 0, 0}, observation);
  EXPECT_EQ(observation[5], static_cast<float>(env.world().joint(0)->GetJointSpeed() / 8.0));
}

TEST(BipedalWalkerTest, FrictionChangeReachesExistingContacts) {
  TwinWalkers twins(10);
  for (int t = 0; t < 40; ++t) twins.Step({0, 1, 0, 1});  // stand on both feet
  BipedalWalker& env = twins.b();
  env.SetFeature(BipedalWalker::kFriction, 0.5);
  twins.Step({0, 1, 0, 1});
  int touching = 0;
  for (const b2Contact* c = env.world().world().GetContactList(); c != nullptr; c = c->GetNext()) {
    const float expected =
        std::sqrt(c->GetFixtureA()->GetFriction() * c->GetFixtureB()->GetFriction());
    EXPECT_FLOAT_EQ(c->GetFriction(), expected);
    const b2Fixture* ground = c->GetFixtureA()->GetBody()->GetType() == b2_staticBody
                                  ? c->GetFixtureA()
                                  : c->GetFixtureB();
    EXPECT_EQ(ground->GetFriction(), 0.5f);
    touching += c->IsTouching();
  }
  EXPECT_GT(touching, 0);
}

TEST(BipedalWalkerTest, GeometryFeaturesWaitForTheNextReset) {
  TwinWalkers twins(11);
  twins.b().SetFeature(BipedalWalker::kScale, 60);
  twins.b().SetFeature(BipedalWalker::kLegH, 1.5);
  twins.b().SetFeature(BipedalWalker::kTerrainLength, 300);
  const auto [ra, rb] = twins.Step({0.2f, 0.2f, 0.2f, 0.2f});
  EXPECT_EQ(ra.reward, rb.reward);
  EXPECT_EQ(twins.b().world().terrain_y().size(), 200u);

  Random random(11);
  Observation observation;
  twins.b().Reset(random, observation);
  EXPECT_EQ(twins.b().world().terrain_y().size(), 300u);
  const auto* upper =
      static_cast<const b2PolygonShape*>(twins.b().world().leg(0)->GetFixtureList()->GetShape());
  EXPECT_FLOAT_EQ(upper->m_vertices[2].y, 0.75f);              // half of LEG_H
  EXPECT_NEAR(HullMass(twins.b()).mass, kHullMass / 4, 1e-4);  // HULL_POLY / 60
}

TEST(BipedalWalkerTest, RendersTheScene) {
  BipedalWalker env = Walker(2.0);
  Random random(0);
  Observation observation;
  env.Reset(random, observation);
  Canvas canvas(600, 400);
  auto pixel = [&canvas](int x, int y) {
    const uint8_t* p = canvas.pixels().data() + 3 * (y * canvas.width() + x);
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  auto count = [&canvas](std::array<int, 3> color) {
    int n = 0;
    for (size_t i = 0; i < canvas.pixels().size(); i += 3) {
      n += canvas.pixels()[i] == color[0] && canvas.pixels()[i + 1] == color[1] &&
           canvas.pixels()[i + 2] == color[2];
    }
    return n;
  };
  env.Render(canvas);
  EXPECT_EQ(pixel(0, 0), (std::array<int, 3>{215, 215, 255}));   // sky
  EXPECT_EQ(pixel(5, 399), (std::array<int, 3>{102, 153, 76}));  // terrain fill
  // The hull origin in pixels: 30 px per metre from the camera's left edge, y up from the
  // bottom. The payload comes first in Box2D's fixture list, so the hull polygon covers it
  // (Gymnasium draws body.fixtures in that order); its lower part shows below the hull, in
  // the hull's outline colour (pygame draws a circle filled in both colours).
  const b2Vec2 hull = env.world().hull()->GetPosition();
  const int hx = static_cast<int>((hull.x - env.scroll()) * 30);
  const int hy = static_cast<int>(400 - hull.y * 30);
  EXPECT_EQ(pixel(hx, hy), (std::array<int, 3>{127, 51, 229}));
  EXPECT_EQ(pixel(hx + 5, hy + 12), (std::array<int, 3>{76, 76, 127}));
  EXPECT_GT(count({128, 51, 102}), 100);  // leg +1, drawn over leg -1
  EXPECT_GT(count({230, 51, 0}), 20);     // flag
  EXPECT_EQ(count({255, 0, 0}), 0);
  env.Render(canvas, 9);
  EXPECT_GT(count({255, 0, 0}), 50);  // the lidar ray nearest to horizontal

  // Walking apart, both legs show.
  WalkerHeuristic gait;
  Action action = {0, 0, 0, 0};
  for (int t = 0; t < 60; ++t) {
    env.Step(action, observation);
    action = gait.Act(observation);
  }
  env.Render(canvas);
  EXPECT_GT(count({178, 101, 152}), 50);  // leg -1
  EXPECT_GT(count({128, 51, 102}), 50);
}

TEST(BipedalWalkerTest, RunsUnderTheDynamicContextWrapperWithAComXSchedule) {
  ScheduleConfig config{.family = "sinusoidal",
                        .params = {{"amplitude_frac", 0.5}, {"period", 50.0}}};
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, -0.6, 0.6, 3);
  ASSERT_TRUE(spec.ok()) << spec.status();
  DynamicContextOptions options{
      .observe = ObserveMode::kLive, .observed_features = {BipedalWalker::kComX}, .run_seed = 5};
  options.pools.push_back({BipedalWalker::kComX, *ContextPool::OfSize(-0.6, 0.6, 3)});
  options.schedules.push_back({BipedalWalker::kComX, {{.steps = 1 << 30, .spec = *spec}}});
  absl::StatusOr<DynamicContextEnv<BipedalWalker>> env =
      DynamicContextEnv<BipedalWalker>::Create(std::move(options));
  ASSERT_TRUE(env.ok()) << env.status();

  Observation observation;
  std::array<float, 1> context;
  env->Reset(0, observation, context);
  WalkerHeuristic gait;
  Action action = {0, 0, 0, 0};
  double lo = 1e9;
  double hi = -1e9;
  for (int t = 0; t < 300; ++t) {
    const StepResult result = env->Step(action, observation, context);
    if (result.done()) {
      env->Reset(t, observation, context);
      gait.Reset();
      action = {0, 0, 0, 0};
      continue;
    }
    action = gait.Act(observation);
    // The payload sits where the schedule put COM_X for this step.
    const double com_x = env->feature(BipedalWalker::kComX);
    const auto* circle =
        static_cast<const b2CircleShape*>(env->env().world().payload()->GetShape());
    ASSERT_EQ(circle->m_p.x, static_cast<float>(com_x)) << t;
    EXPECT_EQ(context[0],
              NormalizeContext(BipedalWalker::Features().feature(BipedalWalker::kComX), com_x));
    lo = std::min(lo, com_x);
    hi = std::max(hi, com_x);
  }
  EXPECT_GT(hi - lo, 0.2);
}

TEST(BipedalWalkerTest, RunsInAVectorEnv) {
  std::vector<DynamicContextOptions> slots;
  for (uint64_t slot = 0; slot < 3; ++slot) {
    DynamicContextOptions options{.run_seed = 9, .slot = slot};
    options.pools.push_back({BipedalWalker::kComX, *ContextPool::OfSize(-0.6, 0.6, 3)});
    slots.push_back(std::move(options));
  }
  absl::StatusOr<VectorEnv<BipedalWalker>> env = VectorEnv<BipedalWalker>::Create(std::move(slots));
  ASSERT_TRUE(env.ok()) << env.status();
  env->Reset();
  Random random(2);
  std::vector<float> actions(3 * 4);
  int episodes_done = 0;
  for (int t = 0; t < 400; ++t) {
    for (float& a : actions) a = static_cast<float>(random.Uniform(-1, 1));
    env->Step(actions);
    for (int i = 0; i < 3; ++i) {
      episodes_done += env->terminated()[i] || env->truncated()[i];
      ASSERT_TRUE(std::isfinite(env->rewards()[i]));
    }
    for (const float o : env->observations()) ASSERT_TRUE(std::isfinite(o));
  }
  EXPECT_GT(episodes_done, 0);  // random actions fall; the slots reset themselves
  EXPECT_EQ(env->global_steps(), 1200);
}

}  // namespace
}  // namespace dcs::env
