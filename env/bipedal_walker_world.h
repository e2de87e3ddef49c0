// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_BIPEDAL_WALKER_WORLD_H_
#define DCS_ENV_BIPEDAL_WALKER_WORLD_H_

// The Box2D side of BipedalWalker-v3 (gymnasium/envs/box2d/bipedal_walker.py), apart from the
// environment adapter as in envpool's split: one b2World reused across episodes, holding the
// terrain (normal or hardcore), the hull with an optional payload fixture (docs/reference.md,
// "Context features and payloads"), two legs of two segments with motorised hip and knee joints,
// the contact flags and the ten lidar rays. It takes plain parameters and knows nothing of
// observations, rewards or context features (env/bipedal_walker.h adapts it).
//
// One deliberate difference from Gymnasium's world: the terrain is one static body at the origin
// holding every terrain fixture (Gymnasium makes a body per edge and obstacle, all at the
// origin). Fixtures, their creation order and so the broad-phase proxies are Gymnasium's; the
// solver sees the same static geometry, so trajectories are bit-identical, while Box2D's
// per-body loops in every step (island flags, force clearing, TOI bookkeeping) shrink from 200
// bodies to 6: 7% of a step (bench/RESULTS.md).
//
// Box2D keeps pointers into this object (it is the world's contact listener), so it is neither
// copyable nor movable: own it through a std::unique_ptr. Thread-compatible.

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "box2d/box2d.h"
#include "common/random.h"

namespace dcs::env {

// Shape and terrain parameters: they apply when the world is rebuilt (WalkerWorld::Build).
// Defaults are Gymnasium's module constants.
struct WalkerGeometry {
  double scale = 30.0;                // pixels per metre; the hull polygon is HULL_POLY / scale
  double terrain_step = 14.0 / 30.0;  // m between terrain points
  int terrain_length = 200;           // terrain points
  double terrain_height = 400.0 / 30.0 / 4;  // m, the start pad's height
  int terrain_grass = 10;                    // grass stretches last [grass / 2, grass) points
  double terrain_startpad = 20;              // flat points before the first random draw
  double leg_down = -8.0 / 30.0;             // m, hip anchor below the hull origin
  double leg_w = 8.0 / 30.0;                 // m, upper leg width (the lower leg is 0.8 of it)
  double leg_h = 34.0 / 30.0;                // m, length of each leg segment
  double initial_random = 5.0;               // N, bound of the initial horizontal push
  double viewport_h = 400;                   // px; sets the clouds' height
  bool hardcore = false;                     // stumps, stairs and pits
};

// A circle fixture on the hull at hull-local (com_x, 0) (the reference `_set_payload_com_x`):
// density mass / (pi radius^2), friction 0, Box2D's default collision filter (category 0x0001,
// mask 0xFFFF), so it touches the terrain and the lower legs like ground does: such a contact
// is a hull contact (game over), and lidar rays starting outside it see it.
struct WalkerPayload {
  double com_x = 0;     // m, hull-local x (forward)
  double mass = 0;      // kg; 0 means no payload
  double radius = 0.5;  // m; 0 means no payload
};

class WalkerWorld final : private b2ContactListener {
 public:
  static constexpr int kNumLidar = 10;
  static constexpr int kNumLegs = 4;  // upper(-1), lower(-1), upper(+1), lower(+1)

  struct Obstacle {  // a hardcore stump, stair step or pit wall, in world coordinates
    std::array<b2Vec2, 4> vertices;
  };
  struct Cloud {  // render only; drawn with parallax
    std::array<b2Vec2, 5> vertices;
    double x1;  // smallest and largest vertex x
    double x2;
  };
  struct LidarRay {  // the last cast: from p1 to the nearest ground hit p2 (or the range end)
    b2Vec2 p1{0, 0};
    b2Vec2 p2{0, 0};
    float fraction = 1;
  };

  // An empty world with gravity (0, -10); Build adds the bodies.
  WalkerWorld();
  ~WalkerWorld() override;
  WalkerWorld(const WalkerWorld&) = delete;
  WalkerWorld& operator=(const WalkerWorld&) = delete;

  // Destroys the previous episode's bodies (without contact callbacks, as Gymnasium detaches
  // its listener) and builds the next: terrain with friction `friction`, clouds, the hull (no
  // payload) with its random horizontal push, and the legs and joints (motor torque
  // `motors_torque` until the first SetMotors), in Gymnasium's creation order. Draws from
  // `random` in Gymnasium's order: terrain, clouds, push. Clears game over and foot contacts.
  void Build(const WalkerGeometry& geometry, double friction, double motors_torque, Random& random);

  void SetGravity(double x, double y);
  // Sets the friction of every terrain fixture and re-mixes the friction of existing contacts,
  // so the change applies in the next step. No-op before the first Build.
  void SetTerrainFriction(double friction);
  // Replaces the payload fixture (none if mass or radius is 0) and recomputes the hull's mass
  // data. REQUIRES: Build was called; payload values finite and non-negative.
  void SetPayload(const WalkerPayload& payload);

  // Gymnasium's motor control: joint j gets speed speed_j * sign(a_j) (speed_hip for joints 0
  // and 2, speed_knee for 1 and 3) and maximum torque motors_torque * clip(|a_j|, 0, 1); then
  // every walker body that is asleep is woken, as pybox2d 2.3's setters do.
  // REQUIRES: Build was called; finite actions.
  void SetMotors(std::span<const float, 4> action, double speed_hip, double speed_knee,
                 double motors_torque);
  // One world step of `dt` seconds with 180 velocity and 60 position iterations.
  void Step(double dt);
  // Casts the ten lidar rays from the hull origin, ray i at 1.5 i / 10 rad from straight down
  // toward +x (world frame), `range` m long; writes each nearest ground fraction (1 if none).
  // The fractions and hit points are those of Gymnasium's b2World::RayCast with its callback
  // (ignore fixtures whose category bit 0 is clear, clip the ray at every other), which reports
  // the nearest hit last. Instead of one tree walk per ray, one tree query collects the fixtures
  // near the rays and each ray tests those whose fat AABB its clipped box overlaps: a hit lies
  // on the shape, well inside the fat AABB (Box2D pads it by 0.1 m), so no hit is skipped, and a
  // shape's hit fraction does not depend on the clipping, so the nearest is the same.
  void CastLidar(double range, std::span<float, kNumLidar> fractions);

  const b2World& world() const { return *world_; }
  const b2Body* hull() const { return hull_; }
  const b2Body* leg(int i) const { return legs_[i]; }  // i < kNumLegs
  // Joints in the observation's order: hip(-1), knee(-1), hip(+1), knee(+1).
  const b2RevoluteJoint* joint(int i) const { return joints_[i]; }
  const b2Fixture* payload() const { return payload_; }  // nullptr without a payload
  // Latched by the contact listener: a hull fixture began a contact.
  bool game_over() const { return game_over_; }
  // The lower leg of side 0 (-1) or 1 (+1) touches ground; a set/clear flag, not a counter.
  bool ground_contact(int side) const { return ground_contact_[side]; }

  const WalkerGeometry& geometry() const { return geometry_; }
  std::span<const double> terrain_x() const { return terrain_x_; }
  std::span<const double> terrain_y() const { return terrain_y_; }
  std::span<const Obstacle> obstacles() const { return obstacles_; }
  std::span<const Cloud> clouds() const { return clouds_; }
  const LidarRay& lidar(int i) const { return lidar_[i]; }

 private:
  // A fixture the lidar can see (category bit 0 set, so not the walker's own parts) whose fat
  // AABB overlaps the box of all ten rays: only these can stop a ray.
  struct LidarCandidate {
    const b2Fixture* fixture;
    int32 child_index;
    b2AABB fat_aabb;
  };
  // b2BroadPhase::Query's callback collecting the candidates.
  struct LidarCandidateCollector {
    bool QueryCallback(int32 proxy_id);
    const b2BroadPhase* broad_phase;
    std::vector<LidarCandidate>* candidates;
  };

  void BeginContact(b2Contact* contact) override;
  void EndContact(b2Contact* contact) override;

  void Destroy();
  void GenerateTerrain(double friction, Random& random);
  void AddObstacle(const std::array<b2Vec2, 4>& vertices, double friction);
  void GenerateClouds(Random& random);
  void CreateWalker(double motors_torque, Random& random);

  std::unique_ptr<b2World> world_;  // ~100 kB (its stack allocator is inline)
  WalkerGeometry geometry_;
  b2Body* ground_ = nullptr;  // the terrain: obstacles, then edges, as fixtures
  b2Body* hull_ = nullptr;
  std::array<b2Body*, kNumLegs> legs_{};
  std::array<b2RevoluteJoint*, kNumLegs> joints_{};
  b2Fixture* payload_ = nullptr;
  bool game_over_ = false;
  std::array<bool, 2> ground_contact_{};
  std::vector<double> terrain_x_;
  std::vector<double> terrain_y_;
  std::vector<Obstacle> obstacles_;
  std::vector<Cloud> clouds_;
  std::array<LidarRay, kNumLidar> lidar_;
  std::vector<LidarCandidate> lidar_candidates_;  // CastLidar's scratch, kept for its capacity
};

}  // namespace dcs::env

#endif  // DCS_ENV_BIPEDAL_WALKER_WORLD_H_
