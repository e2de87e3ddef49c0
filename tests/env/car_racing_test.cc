// Copyright 2026 The DCS Authors.
//
// CarRacing-v3 (Gymnasium car_racing.py, env/car_racing.h): track generation and its draw order,
// tile visiting and rewards, termination and truncation, the payload and the other context
// features, the 96x96 picture, the discrete variant, the wrappers, and the baselines (the
// centre-line driver and random actions).
//
// The full 20-seed centre-line evaluation and the constant-action calibration against
// envpool's figures are DISABLED_ (about 3 s each); run them with
//   build/tests/env/env_car_racing_test --gtest_also_run_disabled_tests
//       --gtest_filter='CarRacingBaselineTest.*'

#include "env/car_racing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/random.h"
#include "env/car_racing_centerline.h"
#include "env/car_racing_track.h"
#include "env/dynamic_context_env.h"
#include "env/schedule_config.h"
#include "env/vector_env.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using Observation = std::vector<uint8_t>;
using ObservationSpan = std::span<uint8_t, CarRacing::kObservationSize>;
using Action = std::array<float, CarRacing::kActionSize>;

ObservationSpan Span(Observation& observation) {
  return ObservationSpan(observation.data(), CarRacing::kObservationSize);
}

Observation NewObservation() { return Observation(CarRacing::kObservationSize, 0); }

Rgb Pixel(const Observation& observation, int row, int col) {
  const uint8_t* p = observation.data() + 3 * (row * CarRacing::kImageWidth + col);
  return {p[0], p[1], p[2]};
}

bool IsRoadGrey(Rgb c) {
  return c.r >= 95 && c.r <= 115 && std::abs(c.r - c.g) <= 2 && std::abs(c.r - c.b) <= 2;
}

struct Episode {
  double total = 0;  // sum of step rewards
  int steps = 0;
  bool terminated = false;
  bool truncated = false;
  StepResult last;
};

Episode DriveCenterline(CarRacing& env, uint64_t seed) {
  Observation observation = NewObservation();
  Random random(seed);
  env.Reset(random, Span(observation));
  CenterlineDriver driver;
  driver.Reset(env);
  Episode episode;
  Action action;
  while (true) {
    driver.Act(env, action);
    episode.last = env.Step(action, Span(observation));
    episode.total += episode.last.reward;
    ++episode.steps;
    if (episode.last.done()) break;
  }
  episode.terminated = episode.last.terminated;
  episode.truncated = episode.last.truncated;
  return episode;
}

// --- Track generation --------------------------------------------------------------------------

TEST(CarRacingTrackTest, TrackClosesWithEvenSpacingAndPlausibleLength) {
  for (uint64_t seed = 0; seed < 20; ++seed) {
    Random random(seed);
    const Track track = GenerateTrack(random);
    const int n = track.size();
    EXPECT_GE(n, 200) << seed;
    EXPECT_LE(n, 400) << seed;
    ASSERT_EQ(static_cast<int>(track.border.size()), n);
    for (int i = 1; i < n; ++i) {
      const double d = std::hypot(track.points[i].x - track.points[i - 1].x,
                                  track.points[i].y - track.points[i - 1].y);
      EXPECT_NEAR(d, kTrackDetailStep, 1e-9) << seed << " " << i;
      // Turns of at most 0.31 rad per point; beta itself may jump by 2 pi.
      const double turn =
          std::remainder(track.points[i].beta - track.points[i - 1].beta, 2 * 3.141592653589793);
      EXPECT_LE(std::abs(turn), kTrackTurnRate + 1e-9) << seed << " " << i;
    }
    // The glue check as Gymnasium computes it, and the plain gap.
    const TrackPoint& first = track.points.front();
    const TrackPoint& last = track.points.back();
    const double gx = std::cos(first.beta) * (first.x - last.x);
    const double gy = std::sin(first.beta) * (first.y - last.y);
    EXPECT_LE(std::hypot(gx, gy), kTrackDetailStep) << seed;
    EXPECT_LE(std::hypot(first.x - last.x, first.y - last.y), 3 * kTrackDetailStep) << seed;
    // The start lies just past the start angle (-pi/12, i.e. 345 degrees) on the +x side.
    EXPECT_GT(first.x, 0) << seed;
  }
}

TEST(CarRacingTrackTest, SameSeedSameTrackOtherSeedOtherTrack) {
  Random a(7);
  Random b(7);
  Random c(8);
  const Track ta = GenerateTrack(a);
  const Track tb = GenerateTrack(b);
  const Track tc = GenerateTrack(c);
  ASSERT_EQ(ta.size(), tb.size());
  for (int i = 0; i < ta.size(); ++i) {
    EXPECT_EQ(ta.points[i].x, tb.points[i].x);
    EXPECT_EQ(ta.points[i].y, tb.points[i].y);
    EXPECT_EQ(ta.points[i].beta, tb.points[i].beta);
  }
  EXPECT_EQ(ta.border, tb.border);
  const bool differs = ta.size() != tc.size() || ta.points[10].x != tc.points[10].x;
  EXPECT_TRUE(differs);
}

// Tile counts and retries for a few seeds, checked against a transcription of Gymnasium's
// _create_track fed with the same random() stream (identical to the last bit on 300 seeds).
TEST(CarRacingTrackTest, KnownSeeds) {
  const std::map<uint64_t, std::pair<int, int>> expected = {
      {0, {319, 1}}, {1, {275, 1}}, {8, {251, 1}}, {19, {350, 1}}};
  for (const auto& [seed, n_attempts] : expected) {
    Random random(seed);
    const Track track = GenerateTrack(random);
    EXPECT_EQ(track.size(), n_attempts.first) << seed;
    EXPECT_EQ(track.attempts, n_attempts.second) << seed;
  }
}

TEST(CarRacingTrackTest, EveryAttemptDrawsTwoUniformsPerCheckpoint) {
  int retried = 0;
  for (uint64_t seed = 0; seed < 100; ++seed) {
    Random generator(seed);
    const Track track = GenerateTrack(generator);
    Random reference(seed);
    for (int i = 0; i < kTrackUniformsPerAttempt * track.attempts; ++i) reference.Uniform01();
    EXPECT_EQ(generator.Uniform01(), reference.Uniform01()) << seed;
    if (track.attempts > 1) {
      ++retried;
      // The first attempt failed, and the retry starts right after its 24 draws.
      Random first(seed);
      EXPECT_FALSE(TryTraceTrack(first).has_value()) << seed;
    }
  }
  EXPECT_GT(retried, 0);  // some seeds need a retry (5 of the first 100)
}

// Kerb flags on a synthetic track: only the tile ending four same-direction turns sharper than
// 0.062 rad gets the raw flag, which spreads to the three tiles before it.
TEST(CarRacingTrackTest, KerbsOnlyOnSharpConsistentTurns) {
  std::vector<TrackPoint> points(30);
  for (int k = 0; k < 30; ++k) {
    points[k].beta = k <= 9 ? 0.0 : (k <= 13 ? 0.1 * (k - 9) : 0.4);
  }
  std::vector<bool> border = ComputeBorders(points);
  for (int k = 0; k < 30; ++k) EXPECT_EQ(border[k], k >= 10 && k <= 13) << k;

  // Turns of 0.05 rad (below 0.2 * 0.31) give no kerb; nor do alternating sharp turns.
  for (int k = 0; k < 30; ++k) points[k].beta = k <= 9 ? 0.0 : (k <= 13 ? 0.05 * (k - 9) : 0.2);
  border = ComputeBorders(points);
  EXPECT_EQ(std::count(border.begin(), border.end(), true), 0);
  for (int k = 0; k < 30; ++k) points[k].beta = (k % 2) * 0.2;
  border = ComputeBorders(points);
  EXPECT_EQ(std::count(border.begin(), border.end(), true), 0);
}

// Gymnasium spreads the flags in place with negative indices, so a raw flag on tile 0 reaches
// back six tiles (N-1 .. N-6) instead of three.
TEST(CarRacingTrackTest, KerbSpreadWrapsInPlaceLikeGymnasium) {
  const int n = 20;
  std::vector<TrackPoint> points(n);
  for (int k = 1; k < 16; ++k) points[k].beta = 0.4;
  points[16].beta = 0.0;
  points[17].beta = 0.1;
  points[18].beta = 0.2;
  points[19].beta = 0.3;
  points[0].beta = 0.4;
  const std::vector<bool> border = ComputeBorders(points);
  for (int k = 0; k < n; ++k) EXPECT_EQ(border[k], k == 0 || k >= 14) << k;
}

TEST(CarRacingTrackTest, GeneratedKerbsFollowSharpTurns) {
  Random random(3);
  const Track track = GenerateTrack(random);
  const int n = track.size();
  auto raw = [&](int i) {
    double oneside = 0;
    for (int k = 0; k < 4; ++k) {
      const double d = track.points[(i - k + n) % n].beta - track.points[(i - k - 1 + n) % n].beta;
      if (std::abs(d) <= 0.31 * 0.2) return false;
      oneside += d > 0 ? 1 : -1;
    }
    return std::abs(oneside) == 4;
  };
  int kerbs = 0;
  for (int i = 0; i < n - 8; ++i) {
    if (!track.border[i]) continue;
    ++kerbs;
    bool origin = false;
    for (int k = 0; k < 4; ++k) origin = origin || raw(i + k);
    EXPECT_TRUE(origin) << i;
  }
  for (int i = 0; i < n; ++i) {
    if (raw(i)) {
      EXPECT_TRUE(track.border[i]) << i;
    }
  }
  EXPECT_GT(kerbs, 0);
  EXPECT_LT(kerbs, n / 2);
}

TEST(CarRacingTrackTest, RoadPolygonsInterleaveKerbs) {
  Random random(3);
  const Track track = GenerateTrack(random);
  const std::vector<RoadPolygon> road = BuildRoadPolygons(track, {102, 102, 102});
  const int kerbs = static_cast<int>(std::count(track.border.begin(), track.border.end(), true));
  ASSERT_EQ(static_cast<int>(road.size()), track.size() + kerbs);
  int tile = 0;
  for (size_t i = 0; i < road.size(); ++i) {
    if (road[i].tile >= 0) {
      EXPECT_EQ(road[i].tile, tile++);
      continue;
    }
    // A kerb follows its tile, white on even tiles and red on odd ones.
    const int owner = road[i - 1].tile;
    ASSERT_GE(owner, 0);
    EXPECT_TRUE(track.border[owner]);
    EXPECT_EQ(road[i].color.g, owner % 2 == 0 ? 255 : 0);
  }
}

// --- Features ------------------------------------------------------------------------------

TEST(CarRacingTest, FeaturesHaveGymnasiumAndPaperDefaults) {
  const ContextSpace& space = CarRacing::Features();
  ASSERT_EQ(space.size(), CarRacing::kNumFeatures);
  EXPECT_EQ(space.feature(CarRacing::kComX).name, "COM_X");
  EXPECT_EQ(space.feature(CarRacing::kComY).name, "COM_Y");
  EXPECT_EQ(space.feature(CarRacing::kComX).normalization_lower, -2.0);
  EXPECT_EQ(space.feature(CarRacing::kComY).normalization_upper, 2.0);
  EXPECT_LE(space.feature(CarRacing::kComY).lower, -2.0);
  EXPECT_GE(space.feature(CarRacing::kComY).upper, 2.0);
  EXPECT_EQ(space.feature(CarRacing::kPayloadMass).default_value, 1.0);
  EXPECT_EQ(space.feature(CarRacing::kPayloadRadius).default_value, 0.5);
  EXPECT_EQ(space.feature(CarRacing::kEnginePower).default_value, 40000.0);
  EXPECT_EQ(space.feature(CarRacing::kFrictionLimit).default_value, 400.0);
  EXPECT_EQ(space.feature(CarRacing::kBrakeForce).default_value, 15.0);
  EXPECT_DOUBLE_EQ(space.feature(CarRacing::kWheelMomentOfInertia).default_value, 1.6);
  EXPECT_EQ(space.feature(CarRacing::kLapCompletePercent).default_value, 0.95);
  EXPECT_TRUE(CarRacing::ValidateContext(space.Defaults()).ok());
  std::vector<double> context = space.Defaults();
  context[CarRacing::kPayloadRadius] = 0.0;
  EXPECT_FALSE(CarRacing::ValidateContext(context).ok());
  context = space.Defaults();
  context[CarRacing::kComX] = -5.5;
  EXPECT_FALSE(CarRacing::ValidateContext(context).ok());
}

// --- Reset, rewards, termination ------------------------------------------------------------

TEST(CarRacingTest, ResetPlacesTheCarAtTheStartAndVisitsTheFirstTiles) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(0);
  env.Reset(random, Span(observation));
  const TrackPoint& start = env.track().points[0];
  const b2Vec2 position = env.car().hull()->GetPosition();
  EXPECT_NEAR(position.x, start.x, 0.05);
  EXPECT_NEAR(position.y, start.y, 0.05);
  EXPECT_NEAR(env.car().hull()->GetAngle(), start.beta, 0.01);
  EXPECT_NEAR(env.time(), 0.02, 1e-12);
  EXPECT_EQ(env.elapsed_steps(), 0);
  // Tile 0 lies under the rear wheels: visited in the reset step (the tile-0 quirk).
  EXPECT_TRUE(env.tile_visited(0));
  EXPECT_GE(env.tiles_visited(), 1);
  EXPECT_LE(env.tiles_visited(), 3);
  EXPECT_NEAR(env.total_reward(), env.tiles_visited() * 1000.0 / env.num_tiles(), 1e-9);
}

TEST(CarRacingTest, ResetTilesArePaidInTheFirstStepThenMinusOneTenthPerStep) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(1);
  env.Reset(random, Span(observation));
  const int at_reset = env.tiles_visited();
  const double per_tile = 1000.0 / env.num_tiles();
  const Action idle = {0, 0, 0};
  const StepResult first = env.Step(idle, Span(observation));
  EXPECT_NEAR(first.reward, at_reset * per_tile - 0.1, 1e-9);
  EXPECT_EQ(env.tiles_visited(), at_reset);  // standing still visits nothing new
  for (int i = 0; i < 20; ++i) {
    const StepResult r = env.Step(idle, Span(observation));
    EXPECT_NEAR(r.reward, -0.1, 1e-9);
    EXPECT_FALSE(r.done());
  }
}

TEST(CarRacingTest, DrivingVisitsEveryTileOnceAndTheLapTerminates) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(1);
  env.Reset(random, Span(observation));
  CenterlineDriver driver;
  driver.Reset(env);
  const int n = env.num_tiles();
  const double per_tile = 1000.0 / n;
  double total = 0;
  int previous_visited = env.tiles_visited();
  int steps = 0;
  Action action;
  StepResult result;
  do {
    driver.Act(env, action);
    result = env.Step(action, Span(observation));
    ++steps;
    total += result.reward;
    const int visited = env.tiles_visited();
    EXPECT_GE(visited, previous_visited);
    EXPECT_LE(visited - previous_visited, 4);
    if (steps > 1) {
      EXPECT_NEAR(result.reward, (visited - previous_visited) * per_tile - 0.1, 1e-9);
    }
    previous_visited = visited;
  } while (!result.done());
  EXPECT_TRUE(result.terminated);
  EXPECT_FALSE(result.truncated);
  EXPECT_LT(steps, CarRacing::kMaxEpisodeSteps);
  EXPECT_EQ(env.tiles_visited(), n);
  for (int i = 0; i < n; ++i) EXPECT_TRUE(env.tile_visited(i)) << i;
  // Every tile paid once, 0.1 per step taken.
  EXPECT_NEAR(total, 1000.0 - 0.1 * steps, 1e-6);
  EXPECT_NEAR(env.total_reward(), total, 1e-6);
}

// With lap_complete_percent = 0 the tile-0 check fires already in the reset step, so the very
// first step terminates (as in Gymnasium v3, where the check sits in the first-visit branch).
TEST(CarRacingTest, LapCompletePercentZeroEndsAtTheFirstStep) {
  CarRacing env;
  env.SetFeature(CarRacing::kLapCompletePercent, 0.0);
  Observation observation = NewObservation();
  Random random(2);
  env.Reset(random, Span(observation));
  const StepResult result = env.Step(Action{0, 0, 0}, Span(observation));
  EXPECT_TRUE(result.terminated);
}

TEST(CarRacingTest, LeavingThePlayfieldCostsOneHundredAndTerminates) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(4);
  env.Reset(random, Span(observation));
  // Moderate gas: full gas spins the rear-driven car into donuts on the grass.
  const Action straight = {0, 0.2f, 0};
  StepResult result;
  int steps = 0;
  do {
    result = env.Step(straight, Span(observation));
    ++steps;
  } while (!result.done());
  EXPECT_TRUE(result.terminated);
  EXPECT_EQ(result.reward, -100);
  const b2Vec2 p = env.car().hull()->GetPosition();
  EXPECT_TRUE(std::abs(p.x) > kPlayfield || std::abs(p.y) > kPlayfield);
  EXPECT_LT(steps, CarRacing::kMaxEpisodeSteps);
}

TEST(CarRacingTest, TruncatesAtOneThousandSteps) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(5);
  env.Reset(random, Span(observation));
  const Action idle = {0, 0, 0};
  for (int t = 1; t <= CarRacing::kMaxEpisodeSteps; ++t) {
    const StepResult r = env.Step(idle, Span(observation));
    EXPECT_FALSE(r.terminated);
    ASSERT_EQ(r.truncated, t == CarRacing::kMaxEpisodeSteps) << t;
  }
}

TEST(CarRacingTest, SameSeedSameTrajectoryAndFrames) {
  CarRacing a;
  CarRacing b;
  Observation oa = NewObservation();
  Observation ob = NewObservation();
  Random ra(11);
  Random rb(11);
  a.Reset(ra, Span(oa));
  b.Reset(rb, Span(ob));
  EXPECT_EQ(oa, ob);
  Random actions(3);
  for (int t = 0; t < 150; ++t) {
    const Action action = {static_cast<float>(actions.Uniform(-1, 1)),
                           static_cast<float>(actions.Uniform(0, 1)),
                           static_cast<float>(actions.Uniform(0, 0.2))};
    const StepResult sa = a.Step(action, Span(oa));
    const StepResult sb = b.Step(action, Span(ob));
    ASSERT_EQ(sa.reward, sb.reward) << t;
    ASSERT_EQ(oa, ob) << t;
  }
  // A reset with another seed gives another picture.
  Random rc(12);
  b.Reset(rc, Span(ob));
  a.Reset(ra, Span(oa));
  EXPECT_NE(oa, ob);
}

// --- Controls and features -----------------------------------------------------------------

TEST(CarRacingTest, GasRampsAndSteeringTurnsTheFrontWheels) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(6);
  env.Reset(random, Span(observation));
  env.Step(Action{0, 1, 0}, Span(observation));
  EXPECT_NEAR(env.car().wheels()[2].gas, 0.1, 1e-12);
  EXPECT_EQ(env.car().wheels()[0].gas, 0.0);
  for (int i = 0; i < 20; ++i) env.Step(Action{1, 1, 0}, Span(observation));
  EXPECT_NEAR(env.car().wheels()[3].gas, 1.0, 1e-12);
  // Steer +1 (right) drives the front joints to their lower limit -0.4.
  EXPECT_NEAR(env.car().wheels()[0].joint->GetJointAngle(), -0.4, 0.02);
  EXPECT_NEAR(env.car().wheels()[2].joint->GetJointAngle(), 0.0, 0.02);
  env.Step(Action{0, 0, 0}, Span(observation));
  EXPECT_EQ(env.car().wheels()[3].gas, 0.0);  // drops at once
  for (int i = 0; i < 10; ++i) env.Step(Action{0, 1, 0}, Span(observation));
  const double spinning = env.car().wheels()[2].omega;
  env.Step(Action{0, 0, 1}, Span(observation));
  // Brake >= 0.9 stops the wheel; the road then spins it up to a fraction of its speed.
  EXPECT_LT(std::abs(env.car().wheels()[2].omega), 0.25 * spinning);
}

double Speed(const CarRacing& env) {
  const b2Vec2 v = env.car().hull()->GetLinearVelocity();
  return std::hypot(v.x, v.y);
}

TEST(CarRacingTest, EnginePowerTakesEffectAtTheNextStep) {
  CarRacing normal;
  CarRacing strong;
  Observation on = NewObservation();
  Observation os = NewObservation();
  Random rn(9);
  Random rs(9);
  normal.Reset(rn, Span(on));
  strong.Reset(rs, Span(os));
  // Light gas: at full gas the rear tyres are at their grip limit whatever the power.
  const Action gas = {0, 0.1f, 0};
  for (int i = 0; i < 10; ++i) {
    normal.Step(gas, Span(on));
    strong.Step(gas, Span(os));
  }
  EXPECT_EQ(Speed(normal), Speed(strong));
  strong.SetFeature(CarRacing::kEnginePower, 4 * normal.GetFeature(CarRacing::kEnginePower));
  EXPECT_EQ(Speed(normal), Speed(strong));  // nothing happens before the next step
  normal.Step(gas, Span(on));
  strong.Step(gas, Span(os));
  EXPECT_GT(Speed(strong), Speed(normal));
  for (int i = 0; i < 10; ++i) {
    normal.Step(gas, Span(on));
    strong.Step(gas, Span(os));
  }
  EXPECT_GT(Speed(strong), 1.2 * Speed(normal));
}

TEST(CarRacingTest, LowerGripAndWeakerBrakesChangeTheDynamics) {
  auto speed_after_braking = [](double brake_force) {
    CarRacing env;
    env.SetFeature(CarRacing::kBrakeForce, brake_force);
    Observation observation = NewObservation();
    Random random(9);
    env.Reset(random, Span(observation));
    for (int i = 0; i < 40; ++i) env.Step(Action{0, 1, 0}, Span(observation));
    for (int i = 0; i < 10; ++i) env.Step(Action{0, 0, 0.5}, Span(observation));
    return Speed(env);
  };
  EXPECT_GT(speed_after_braking(3.0), speed_after_braking(30.0));

  auto yaw_rate_in_turn = [](double friction) {
    CarRacing env;
    env.SetFeature(CarRacing::kFrictionLimit, friction);
    Observation observation = NewObservation();
    Random random(9);
    env.Reset(random, Span(observation));
    for (int i = 0; i < 30; ++i) env.Step(Action{0, 1, 0}, Span(observation));
    for (int i = 0; i < 10; ++i) env.Step(Action{-1, 0, 0}, Span(observation));
    return std::abs(env.car().hull()->GetAngularVelocity());
  };
  EXPECT_NE(yaw_rate_in_turn(100.0), yaw_rate_in_turn(400.0));
}

// --- Payload ---------------------------------------------------------------------------------

Car::MassData MassAfterReset(double payload_mass, double com_x, double com_y) {
  CarRacing env;
  env.SetFeature(CarRacing::kPayloadMass, payload_mass);
  env.SetFeature(CarRacing::kComX, com_x);
  env.SetFeature(CarRacing::kComY, com_y);
  Observation observation = NewObservation();
  Random random(0);
  env.Reset(random, Span(observation));
  return env.car().GetMassData();
}

TEST(CarRacingTest, PayloadAddsItsMassAndShiftsTheCentreOfMass) {
  const Car::MassData bare = MassAfterReset(0.0, 0, 0);
  // Gymnasium's car: hull 7.06 with its centre of mass at (0, -0.0825); wheels 0.06048 each.
  EXPECT_NEAR(bare.rigid_mass, 7.06, 0.01);
  EXPECT_NEAR(bare.rigid_center.x, 0.0, 1e-4);
  EXPECT_NEAR(bare.rigid_center.y, -0.0825, 1e-3);
  EXPECT_NEAR(bare.total_mass, 7.06 + 4 * 0.06048, 0.01);
  {
    CarRacing env;
    env.SetFeature(CarRacing::kPayloadMass, 0.0);
    Observation observation = NewObservation();
    Random random(0);
    env.Reset(random, Span(observation));
    const b2Body& hull = *env.car().hull();
    const b2Vec2 c = hull.GetLocalCenter();
    // GetInertia is about the body origin; Gymnasium's figure is about the centre of mass.
    EXPECT_NEAR(hull.GetInertia() - hull.GetMass() * (c.x * c.x + c.y * c.y), 18.2123, 0.01);
    EXPECT_NEAR(env.car().wheels()[0].body->GetMass(), 0.06048, 1e-5);
  }

  const Car::MassData loaded = MassAfterReset(1.0, 1.0, -0.5);
  EXPECT_NEAR(loaded.total_mass - bare.total_mass, 1.0, 1e-4);
  EXPECT_NEAR(loaded.rigid_mass - bare.rigid_mass, 1.0, 1e-4);
  const double m = bare.rigid_mass;
  EXPECT_NEAR(loaded.rigid_center.x, (m * bare.rigid_center.x + 1.0) / (m + 1.0), 1e-3);
  EXPECT_NEAR(loaded.rigid_center.y, (m * bare.rigid_center.y - 0.5) / (m + 1.0), 1e-3);

  const Car::MassData heavy = MassAfterReset(4.0, 0, 1.5);
  EXPECT_NEAR(heavy.total_mass - bare.total_mass, 4.0, 1e-3);
  EXPECT_NEAR(heavy.rigid_center.y, (m * bare.rigid_center.y + 4 * 1.5) / (m + 4), 1e-3);
}

TEST(CarRacingTest, MovingThePayloadTakesEffectAtTheNextStep) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(0);
  env.Reset(random, Span(observation));
  for (int i = 0; i < 30; ++i) env.Step(Action{0, 1, 0}, Span(observation));
  const b2Body* before = env.car().payload();
  ASSERT_NE(before, nullptr);
  EXPECT_EQ(env.car().payload_spec().x, 0.0);

  env.SetFeature(CarRacing::kComX, 0.8);
  EXPECT_EQ(env.car().payload_spec().x, 0.0);  // not yet
  const double speed = Speed(env);
  env.Step(Action{0, 1, 0}, Span(observation));
  EXPECT_EQ(env.car().payload_spec().x, 0.8);
  const b2Body* payload = env.car().payload();
  ASSERT_NE(payload, nullptr);
  // Welded at hull-local (0.8, 0), moving with the car (its velocity was handed over).
  const b2Vec2 local = env.car().hull()->GetLocalPoint(payload->GetPosition());
  EXPECT_NEAR(local.x, 0.8, 0.02);
  EXPECT_NEAR(local.y, 0.0, 0.02);
  EXPECT_NEAR(Speed(env), speed, 0.1 * speed + 1.0);
  const b2Vec2 pv = payload->GetLinearVelocity();
  const b2Vec2 hv = env.car().hull()->GetLinearVelocity();
  EXPECT_NEAR(pv.x, hv.x, 0.1 * speed + 0.5);
  EXPECT_NEAR(pv.y, hv.y, 0.1 * speed + 0.5);
  const Car::MassData data = env.car().GetMassData();
  EXPECT_GT(data.rigid_center.x, 0.05);

  // Mass 0 removes the payload at the next step.
  env.SetFeature(CarRacing::kPayloadMass, 0.0);
  env.Step(Action{0, 1, 0}, Span(observation));
  EXPECT_EQ(env.car().payload(), nullptr);
  EXPECT_NEAR(env.car().GetMassData().rigid_center.x, 0.0, 1e-4);
}

TEST(CarRacingTest, PayloadIsDrawnInCyan) {
  CarRacing env;
  env.SetFeature(CarRacing::kComY, 1.0);
  Observation observation = NewObservation();
  Random random(0);
  env.Reset(random, Span(observation));
  for (int i = 0; i < 60; ++i) env.Step(Action{0, 0, 0}, Span(observation));
  int cyan = 0;
  for (int row = 60; row < 80; ++row) {
    for (int col = 40; col < 56; ++col) {
      const Rgb c = Pixel(observation, row, col);
      cyan += c.r < 120 && c.g > 150 && c.b > 150;
    }
  }
  EXPECT_GT(cyan, 0);
}

// --- Picture -------------------------------------------------------------------------------

TEST(CarRacingTest, PictureShowsCarRoadGrassAndIndicatorBar) {
  CarRacing env;
  env.SetFeature(CarRacing::kPayloadMass, 0.0);
  Observation observation = NewObservation();
  Random random(0);
  env.Reset(random, Span(observation));
  // The first picture is zoomed out (t = 0.02 s): the whole playfield with black around it.
  int black = 0;
  for (int row = 0; row < 84; ++row) {
    for (int col = 0; col < 96; ++col) {
      const Rgb c = Pixel(observation, row, col);
      black += c.r == 0 && c.g == 0 && c.b == 0;
    }
  }
  EXPECT_GT(black, 96 * 84 / 4);

  // After 1 s at rest the zoom is full (16.2 px per unit).
  for (int i = 0; i < 60; ++i) env.Step(Action{0, 0, 0}, Span(observation));
  // The red car near the bottom centre (window (500, 600) -> (48, 72)), pointing up.
  int red = 0;
  int top_red_row = 96;
  int bottom_red_row = 0;
  for (int row = 60; row < 84; ++row) {
    for (int col = 42; col < 55; ++col) {
      const Rgb c = Pixel(observation, row, col);
      if (c.r > 120 && c.g < 60 && c.b < 60) {
        ++red;
        top_red_row = std::min(top_red_row, row);
        bottom_red_row = std::max(bottom_red_row, row);
      }
    }
  }
  EXPECT_GT(red, 6);
  EXPECT_GE(top_red_row, 64);
  EXPECT_LE(bottom_red_row, 80);
  // The front wing (wide, at the top) is wider than the rear (120 vs 100 px).
  // Road under and around the car, on both sides.
  EXPECT_TRUE(IsRoadGrey(Pixel(observation, 72, 42)));
  EXPECT_TRUE(IsRoadGrey(Pixel(observation, 72, 54)));
  EXPECT_TRUE(IsRoadGrey(Pixel(observation, 50, 48)));
  // Grass somewhere.
  int green = 0;
  for (int row = 0; row < 84; ++row) {
    for (int col = 0; col < 96; ++col) {
      const Rgb c = Pixel(observation, row, col);
      green += c.g > c.r + 60 && c.g > c.b + 60;
    }
  }
  EXPECT_GT(green, 500);
  // The indicator bar: rows 84-95 mostly black (the car is at rest: no bars but the score).
  int bar_black = 0;
  for (int row = 84; row < 96; ++row) {
    for (int col = 0; col < 96; ++col) {
      const Rgb c = Pixel(observation, row, col);
      bar_black += c.r < 10 && c.g < 10 && c.b < 10;
    }
  }
  EXPECT_GT(bar_black, 96 * 12 * 8 / 10);
  // The score "0000"-ish smudge at the left of the bar.
  int text = 0;
  for (int row = 86; row < 95; ++row) {
    for (int col = 0; col < 12; ++col) text += Pixel(observation, row, col).r > 60;
  }
  EXPECT_GT(text, 5);
}

TEST(CarRacingTest, IndicatorsShowSpeedAndWheelSpin) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(0);
  env.Reset(random, Span(observation));
  for (int i = 0; i < 60; ++i) env.Step(Action{0, 1, 0}, Span(observation));
  // Speed: white bar at window x 125..150 -> columns 12-14, above row 93.
  int white = 0;
  for (int row = 84; row < 94; ++row) {
    white += Pixel(observation, row, 13).r > 200 && Pixel(observation, row, 13).b > 200;
  }
  EXPECT_GT(white, 1);
  // Rear-wheel spin: (51, 0, 255) bars at window x 225..275 -> columns 22-26.
  int blue = 0;
  for (int row = 84; row < 94; ++row) blue += Pixel(observation, row, 24).b > 200;
  EXPECT_GT(blue, 1);
}

TEST(CarRacingTest, KerbsAppearAlongTheTrack) {
  CarRacing env;
  Observation observation = NewObservation();
  Random random(3);
  env.Reset(random, Span(observation));
  CenterlineDriver driver;
  driver.Reset(env);
  int kerb_frames = 0;
  Action action;
  for (int t = 0; t < 400; ++t) {
    driver.Act(env, action);
    if (env.Step(action, Span(observation)).done()) break;
    int white = 0;
    int red = 0;
    for (int row = 0; row < 60; ++row) {
      for (int col = 0; col < 96; ++col) {
        const Rgb c = Pixel(observation, row, col);
        white += c.r > 230 && c.g > 230 && c.b > 230;
        red += c.r > 230 && c.g < 40 && c.b < 40;  // kerb red (255, 0, 0), not the car's 204
      }
    }
    kerb_frames += white > 0 && red > 0;
  }
  EXPECT_GT(kerb_frames, 10);
}

TEST(CarRacingTest, RenderDrawsTheWindowAtAnySize) {
  CarRacing env;
  env.SetFeature(CarRacing::kPayloadMass, 0.0);  // else the cyan payload covers the hull centre
  Observation observation = NewObservation();
  Random random(0);
  env.Reset(random, Span(observation));
  for (int i = 0; i < 60; ++i) env.Step(Action{0, 0, 0}, Span(observation));
  Canvas frame(CarRacing::kRenderWidth, CarRacing::kRenderHeight);
  env.Render(frame);
  // The car at window (500, 599) -> (300, 300) in the 600x400 frame.
  const uint8_t* p = frame.pixels().data() + 3 * (300 * 600 + 300);
  EXPECT_EQ(p[0], 204);
  EXPECT_EQ(p[1], 0);
  // The bottom eighth is the black bar.
  const uint8_t* q = frame.pixels().data() + 3 * (395 * 600 + 590);
  EXPECT_EQ(q[0] + q[1] + q[2], 0);
}

TEST(CarRacingTest, DomainRandomizeDrawsColoursBeforeTheTrack) {
  CarRacing plain;
  CarRacing randomized(CarRacingOptions{.domain_randomize = true});
  Observation op = NewObservation();
  Observation orr = NewObservation();
  Random rp(5);
  Random rr(5);
  plain.Reset(rp, Span(op));
  randomized.Reset(rr, Span(orr));
  // 7 colour draws (6 uniforms and an integer) come first, so the track differs.
  EXPECT_FALSE(plain.num_tiles() == randomized.num_tiles() &&
               plain.track().points[5].x == randomized.track().points[5].x);
  EXPECT_NE(op, orr);
}

// --- Discrete variant, wrappers ------------------------------------------------------------

TEST(CarRacingTest, DiscreteActionsSteerGasAndBrake) {
  CarRacingDiscrete env;
  Observation observation = NewObservation();
  Random random(0);
  env.Reset(random, Span(observation));
  const std::array<int32_t, 1> gas = {3};
  for (int i = 0; i < 30; ++i) env.Step(gas, Span(observation));
  EXPECT_NEAR(env.base().car().wheels()[2].gas, 0.2, 1e-12);
  EXPECT_GT(Speed(env.base()), 1.0);
  const std::array<int32_t, 1> left = {2};
  for (int i = 0; i < 10; ++i) env.Step(left, Span(observation));
  EXPECT_NEAR(env.base().car().wheels()[0].steer, 0.6, 1e-12);
  EXPECT_GT(env.base().car().wheels()[0].joint->GetJointAngle(), 0.3);  // left is positive
  EXPECT_EQ(env.base().car().wheels()[2].gas, 0.0);                     // gas released
  const std::array<int32_t, 1> brake = {4};
  env.Step(brake, Span(observation));
  EXPECT_NEAR(env.base().car().wheels()[1].brake, 0.8, 1e-12);
}

ScheduleSpec SineSpec(double lo, double hi) {
  ScheduleConfig config;
  config.family = "sinusoidal";
  config.params = {{"amplitude_frac", 0.5}, {"period", 20.0}};
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, lo, hi, 1);
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.ok() ? *spec : ScheduleSpec{};
}

TEST(CarRacingTest, RunsUnderTheDynamicContextWrapperWithACom_YSchedule) {
  DynamicContextOptions options{
      .observe = ObserveMode::kLive, .observed_features = {CarRacing::kComY}, .run_seed = 3};
  options.schedules.push_back(
      {CarRacing::kComY, {{.steps = 1 << 30, .spec = SineSpec(-0.8, 0.8)}}});
  absl::StatusOr<DynamicContextEnv<CarRacing>> env =
      DynamicContextEnv<CarRacing>::Create(std::move(options));
  ASSERT_TRUE(env.ok()) << env.status();
  Observation observation = NewObservation();
  std::array<float, 1> context;
  env->Reset(0, Span(observation), context);
  std::vector<double> seen;
  for (int t = 0; t < 40; ++t) {
    const StepResult r = env->Step(Action{0, 0.5, 0}, Span(observation), context);
    ASSERT_FALSE(r.done());
    const double com_y = env->feature(CarRacing::kComY);
    seen.push_back(com_y);
    // The payload follows the schedule in the same step.
    EXPECT_EQ(env->env().car().payload_spec().y, com_y);
    EXPECT_NEAR(context[0], com_y / 2.0, 1e-6);
  }
  std::sort(seen.begin(), seen.end());
  EXPECT_GT(seen.back() - seen.front(), 0.3);
}

TEST(CarRacingTest, RunsInAVectorOfSlots) {
  std::vector<DynamicContextOptions> slots(2);
  slots[0].slot = 0;
  slots[1].slot = 1;
  absl::StatusOr<VectorEnv<CarRacing>> env = VectorEnv<CarRacing>::Create(std::move(slots));
  ASSERT_TRUE(env.ok()) << env.status();
  env->Reset();
  const std::vector<float> actions = {0, 0.5, 0, 0, 0.3, 0};
  for (int t = 0; t < 5; ++t) env->Step(actions);
  EXPECT_EQ(env->global_steps(), 10);
  EXPECT_FALSE(env->slot(0).env().num_tiles() == env->slot(1).env().num_tiles() &&
               env->slot(0).env().track().points[3].x == env->slot(1).env().track().points[3].x);
}

TEST(CarRacingTest, DiscreteVariantRunsUnderTheWrapper) {
  absl::StatusOr<DynamicContextEnv<CarRacingDiscrete>> env =
      DynamicContextEnv<CarRacingDiscrete>::Create({});
  ASSERT_TRUE(env.ok()) << env.status();
  Observation observation = NewObservation();
  std::span<float> no_context;
  env->Reset(0, Span(observation), no_context);
  for (int32_t a = 0; a < CarRacingDiscrete::kNumActions; ++a) {
    const std::array<int32_t, 1> action = {a};
    EXPECT_FALSE(env->Step(action, Span(observation), no_context).done());
  }
}

// --- Baselines -----------------------------------------------------------------------------

TEST(CarRacingBaselineTest, CenterlineDriverFinishesLaps) {
  CarRacing env;
  double total = 0;
  for (uint64_t seed = 0; seed < 3; ++seed) {
    const Episode episode = DriveCenterline(env, seed);
    total += episode.total;
  }
  EXPECT_GE(total / 3, 800);
}

TEST(CarRacingBaselineTest, DISABLED_CenterlineDriverOver20Seeds) {
  CarRacing env;
  double total = 0;
  int finished = 0;
  for (uint64_t seed = 0; seed < 20; ++seed) {
    const Episode episode = DriveCenterline(env, seed);
    total += episode.total;
    finished += episode.terminated;
    std::printf("seed %2d: %7.1f in %4d steps (%s)\n", static_cast<int>(seed), episode.total,
                episode.steps, episode.terminated ? "lap" : "time limit");
  }
  std::printf("mean over 20 seeds: %.1f, %d laps\n", total / 20, finished);
  EXPECT_GE(total / 20, 800);
}

// envpool's CarRacing-v2 test figures (same physics, other seeds and Box2D 2.3): mean 100-step
// return over 100 seeds with constant actions. DCS gives 64.2, 18.1 and 41.2 without payload.
TEST(CarRacingBaselineTest, DISABLED_ConstantActionCalibration) {
  const std::array<std::pair<Action, double>, 3> cases = {
      {{{0, 0.5f, 0}, 65.0}, {{0.1f, 0.3f, 0}, 18.5}, {{0, 0.7f, 0.1f}, 42.7}}};
  Observation observation = NewObservation();
  for (const auto& [action, expected] : cases) {
    double total = 0;
    for (uint64_t seed = 0; seed < 100; ++seed) {
      CarRacing env;
      env.SetFeature(CarRacing::kPayloadMass, 0.0);
      Random random(seed);
      env.Reset(random, Span(observation));
      for (int t = 0; t < 100; ++t) {
        const StepResult result = env.Step(action, Span(observation));
        total += result.reward;
        if (result.done()) break;
      }
    }
    std::printf("[%.1f %.1f %.1f]: %.2f (envpool %.1f)\n", action[0], action[1], action[2],
                total / 100, expected);
    EXPECT_NEAR(total / 100, expected, 0.1 * expected);
  }
}

TEST(CarRacingBaselineTest, RandomActionsScoreBelowZero) {
  CarRacing env;
  Observation observation = NewObservation();
  double total = 0;
  constexpr int kEpisodes = 10;
  for (uint64_t seed = 0; seed < kEpisodes; ++seed) {
    Random random(seed);
    env.Reset(random, Span(observation));
    Random actions(100 + seed);
    StepResult result;
    do {
      Action action;
      for (int i = 0; i < CarRacing::kActionSize; ++i) {
        action[i] = static_cast<float>(
            actions.Uniform(CarRacing::kActionLow[i], CarRacing::kActionHigh[i]));
      }
      result = env.Step(action, Span(observation));
      total += result.reward;
    } while (!result.done());
  }
  std::printf("random actions: mean return %.1f over %d seeds\n", total / kEpisodes, kEpisodes);
  EXPECT_LT(total / kEpisodes, 0);
}

}  // namespace
}  // namespace dcs::env
