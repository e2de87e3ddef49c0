// Copyright 2026 The DCS Authors.
#include "env/car_racing.h"

#include <array>
#include <cassert>
#include <cmath>
#include <vector>

#include "common/status_macros.h"
#include "env/car_racing_render.h"

namespace dcs::env {
namespace {

struct ColorF {
  double r;
  double g;
  double b;
};

// pygame converts colour components with int() (truncation).
Rgb Truncate(const ColorF& c) {
  return {static_cast<uint8_t>(c.r), static_cast<uint8_t>(c.g), static_cast<uint8_t>(c.b)};
}

}  // namespace

// Everything of an episode, on the heap so that Box2D's pointers to the contact listener stay
// valid when the CarRacing moves.
struct CarRacing::State final : public b2ContactListener {
  explicit State(const CarRacingOptions& opts)
      : options(opts), renderer(opts.supersample), features(Features().Defaults()) {}

  ~State() override {
    car.reset();  // the car refers to the world
    world.reset();
  }

  void BeginContact(b2Contact* contact) override { Contact(contact, true); }
  void EndContact(b2Contact* contact) override { Contact(contact, false); }

  // Gymnasium's FrictionDetector._contact, with fixture tags for its body
  // user data (tiles and wheels).
  void Contact(b2Contact* contact, bool begin) {
    const uintptr_t u1 = contact->GetFixtureA()->GetUserData().pointer;
    const uintptr_t u2 = contact->GetFixtureB()->GetUserData().pointer;
    int tile = -1;
    uintptr_t obj = 0;
    if (CarRacingFixtureTagKind(u1) == CarRacingFixtureKind::kTile) {
      tile = CarRacingFixtureTagIndex(u1);
      obj = u2;
    }
    if (CarRacingFixtureTagKind(u2) == CarRacingFixtureKind::kTile) {
      tile = CarRacingFixtureTagIndex(u2);
      obj = u1;
    }
    if (tile < 0) return;
    tile_colors[tile] = Truncate(road_color);  // anything touching a tile removes its shading
    if (CarRacingFixtureTagKind(obj) != CarRacingFixtureKind::kWheel || car == nullptr) return;
    const int wheel = CarRacingFixtureTagIndex(obj);
    if (begin) {
      car->AddWheelTileContact(wheel, +1);
      if (!tile_visited[tile]) {
        tile_visited[tile] = 1;
        const int n = track.size();
        reward += 1000.0 / n;
        ++tile_visited_count;
        // Checked only on a first visit: tile 0 is visited in the reset step, so in practice
        // the lap ends when every tile has been visited (Gymnasium issue #1269).
        if (tile == 0 &&
            static_cast<double>(tile_visited_count) / n > features[kLapCompletePercent]) {
          new_lap = true;
        }
      }
    } else {
      car->AddWheelTileContact(wheel, -1);
    }
  }

  PayloadSpec Payload() const {
    return {.x = features[kComX],
            .y = features[kComY],
            .mass = features[kPayloadMass],
            .radius = features[kPayloadRadius]};
  }

  CarParams Params() const {
    return {.engine_power = features[kEnginePower],
            .wheel_moment_of_inertia = features[kWheelMomentOfInertia],
            .friction_limit = features[kFrictionLimit],
            .brake_force = features[kBrakeForce]};
  }

  CarRacingFrame Frame() const {
    return {.car = car.get(),
            .road = road,
            .tile_colors = tile_colors,
            .colors = colors,
            .time = t,
            .score = reward};
  }

  CarRacingOptions options;
  CarRacingObservationRenderer renderer;
  std::vector<double> features;

  std::unique_ptr<b2World> world;
  std::unique_ptr<Car> car;
  Track track;
  std::vector<RoadPolygon> road;
  std::vector<Rgb> tile_colors;
  std::vector<uint8_t> tile_visited;
  ColorF road_color = {102, 102, 102};
  CarRacingColors colors;

  double reward = 0;
  double prev_reward = 0;
  double t = 0;
  int tile_visited_count = 0;
  bool new_lap = false;
  int elapsed_steps = 0;
};

const ContextSpace& CarRacing::Features() {
  static const ContextSpace* features = new ContextSpace({
      {"COM_X", "payload position, hull-local x: lateral, positive to the right, m", 0.0, -5.0, 5.0,
       -2.0, 2.0},
      {"COM_Y", "payload position, hull-local y: longitudinal, positive forward, m", 0.0, -3.0, 3.0,
       -2.0, 2.0},
      {"PAYLOAD_MASS", "payload mass, kg (0: no payload)", 1.0, 0.0, 20.0, 0.0, 10.0},
      {"PAYLOAD_RADIUS", "payload radius (16-gon circumradius), m", 0.5, 0.05, 2.0, 0.05, 2.0},
      {"ENGINE_POWER", "engine power per driven (rear) wheel, W", kCarEnginePower, 0.0,
       10 * kCarEnginePower, 0.0, 4 * kCarEnginePower},
      {"FRICTION_LIMIT", "tyre grip: largest tyre force on the road, N (grass: 0.6 of it)",
       kCarFrictionLimit, 0.0, 10 * kCarFrictionLimit, 0.0, 4 * kCarFrictionLimit},
      {"BRAKE_FORCE", "wheel speed removed per step at full (< 0.9) brake, rad/s", kCarBrakeForce,
       0.0, 10 * kCarBrakeForce, 0.0, 4 * kCarBrakeForce},
      // Below ~0.24 the explicit wheel-speed update is unstable at 50 steps per second.
      {"WHEEL_MOMENT_OF_INERTIA", "moment of inertia of each wheel, kg m^2",
       kCarWheelMomentOfInertia, 0.25, 10 * kCarWheelMomentOfInertia, 0.25,
       4 * kCarWheelMomentOfInertia},
      {"LAP_COMPLETE_PERCENT", "fraction of tiles that completes a lap when tile 0 is reached",
       0.95, 0.0, 1.0, 0.0, 1.0},
  });
  return *features;
}

absl::Status CarRacing::ValidateContext(std::span<const double> values) {
  for (int i = 0; i < kNumFeatures; ++i) DCS_RETURN_IF_ERROR(Features().Validate(i, values[i]));
  return absl::OkStatus();
}

CarRacing::CarRacing() : CarRacing(CarRacingOptions()) {}
CarRacing::CarRacing(const CarRacingOptions& options) : state_(std::make_unique<State>(options)) {}
CarRacing::~CarRacing() = default;
CarRacing::CarRacing(CarRacing&&) noexcept = default;
CarRacing& CarRacing::operator=(CarRacing&&) noexcept = default;

double CarRacing::GetFeature(int feature) const { return state_->features[feature]; }

void CarRacing::SetFeature(int feature, double value) { state_->features[feature] = value; }

const Track& CarRacing::track() const { return state_->track; }
const Car& CarRacing::car() const { return *state_->car; }
int CarRacing::tiles_visited() const { return state_->tile_visited_count; }
bool CarRacing::tile_visited(int tile) const { return state_->tile_visited[tile] != 0; }
double CarRacing::total_reward() const { return state_->reward; }
double CarRacing::time() const { return state_->t; }
int CarRacing::elapsed_steps() const { return state_->elapsed_steps; }

void CarRacing::Reset(Random& random, std::span<uint8_t, kObservationSize> observation) {
  State& s = *state_;
  s.car.reset();
  s.world = std::make_unique<b2World>(b2Vec2(0, 0));  // CarRacing passes gravity (0, 0)
  s.world->SetContactListener(&s);
  s.reward = 0;
  s.prev_reward = 0;
  s.tile_visited_count = 0;
  s.t = 0;
  s.new_lap = false;
  s.elapsed_steps = 0;

  ColorF bg = {102, 204, 102};
  ColorF grass = {102, 230, 102};
  s.road_color = {102, 102, 102};
  if (s.options.domain_randomize) {
    s.road_color.r = random.Uniform(0, 210);
    s.road_color.g = random.Uniform(0, 210);
    s.road_color.b = random.Uniform(0, 210);
    bg.r = random.Uniform(0, 210);
    bg.g = random.Uniform(0, 210);
    bg.b = random.Uniform(0, 210);
    grass = bg;
    const int64_t idx = random.Integers(0, 3);
    (idx == 0 ? grass.r : idx == 1 ? grass.g : grass.b) += 20;
  }
  s.colors = {.background = Truncate(bg), .grass = Truncate(grass), .road = Truncate(s.road_color)};

  s.track = GenerateTrack(random);
  s.road = BuildRoadPolygons(s.track, s.colors.road);
  const int n = s.track.size();
  s.tile_colors.resize(n);
  s.tile_visited.assign(n, 0);
  // Gymnasium makes a static body per tile. One static body holding the tiles as fixtures, in
  // the same order, gives the same proxies and contacts while Box2D's per-body loops in every
  // step shrink from ~300 bodies to 6; so the contact listener reads fixture tags.
  b2BodyDef road_def;  // static, at the origin
  b2Body* road = s.world->CreateBody(&road_def);
  for (const RoadPolygon& polygon : s.road) {
    if (polygon.tile < 0) continue;
    const int i = polygon.tile;
    const double shade = 0.01 * (i % 3) * 255;
    s.tile_colors[i] =
        Truncate({s.road_color.r + shade, s.road_color.g + shade, s.road_color.b + shade});
    b2Vec2 vertices[4];
    for (int k = 0; k < 4; ++k) {
      vertices[k].Set(static_cast<float>(polygon.points[k].x),
                      static_cast<float>(polygon.points[k].y));
    }
    b2PolygonShape shape;
    shape.Set(vertices, 4);
    b2FixtureDef fixture;
    fixture.shape = &shape;
    fixture.isSensor = true;
    fixture.userData.pointer = CarRacingFixtureTag(CarRacingFixtureKind::kTile, i);
    road->CreateFixture(&fixture);
  }

  const TrackPoint& start = s.track.points[0];
  s.car = std::make_unique<Car>(*s.world, start.beta, start.x, start.y);
  StepWithControls(nullptr, observation);
}

StepResult CarRacing::Step(std::span<const float, kActionSize> action,
                           std::span<uint8_t, kObservationSize> observation) {
  const double controls[3] = {-static_cast<double>(action[0]), static_cast<double>(action[1]),
                              static_cast<double>(action[2])};
  return StepWithControls(controls, observation);
}

StepResult CarRacing::StepWithControls(const double* controls,
                                       std::span<uint8_t, kObservationSize> observation) {
  State& s = *state_;
  assert(s.car != nullptr && "Step before Reset");
  s.car->SetPayload(s.Payload());
  if (controls != nullptr) {
    s.car->Steer(controls[0]);
    s.car->Gas(controls[1]);
    s.car->Brake(controls[2]);
  }
  constexpr double kDt = 1.0 / kFps;
  s.car->Step(kDt, s.Params());
  s.world->Step(static_cast<float>(kDt), 6 * 30, 2 * 30);
  s.t += kDt;
  s.renderer.Render(s.Frame(), observation);

  StepResult result;
  if (controls == nullptr) return result;
  s.reward -= 0.1;
  result.reward = s.reward - s.prev_reward;
  s.prev_reward = s.reward;
  if (s.tile_visited_count == s.track.size() || s.new_lap) result.terminated = true;
  const b2Vec2 position = s.car->hull()->GetPosition();
  if (std::abs(position.x) > kPlayfield || std::abs(position.y) > kPlayfield) {
    result.terminated = true;
    result.reward = -100;
  }
  result.truncated = ++s.elapsed_steps >= kMaxEpisodeSteps;
  return result;
}

void CarRacing::Render(Canvas& canvas) const {
  assert(state_->car != nullptr && "Render before Reset");
  DrawCarRacingFrame(state_->Frame(), canvas);
}

StepResult CarRacingDiscrete::Step(std::span<const int32_t, kActionSize> action,
                                   std::span<uint8_t, kObservationSize> observation) {
  const int32_t a = action[0];
  assert(a >= 0 && a < kNumActions);
  const double controls[3] = {-0.6 * (a == 1) + 0.6 * (a == 2), 0.2 * (a == 3), 0.8 * (a == 4)};
  return env_.StepWithControls(controls, observation);
}

}  // namespace dcs::env
