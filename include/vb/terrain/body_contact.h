// vb's own body-body contact generation against the static world (docs/architecture.md
// "Contact"): a convex body piece (chassis envelope) against the terrain height field and the
// obstacles, and a wheel cylinder against the obstacles. Stateless: the contacts of a step are a
// function of the poses alone, which is what lets an episode be snapshotted and restored bit for
// bit. The physics adapter solves the contacts (non-penetration and Coulomb friction) inside its
// constraint solver.
//
// Method (convex shapes, engine/convex_shape.h): a point sample of one shape (its vertices and
// points along its edges) inside the other is a contact whose normal is the other shape's face of
// least penetration; against the ground, a sample below the surface is a contact along the
// surface normal, and a terrain grid vertex inside the body is a contact along the body's face.
// The surface is piecewise linear between the grid vertices, so vertices and edge samples find
// every touch up to the sample spacing. A wheel against an obstacle: obstacle samples inside the
// cylinder push it radially (how a wheel climbs an edge), and the cylinder's deepest point below
// an obstacle face pushes along that face (a wheel on a rock's top, a side wall against a face).
#pragma once

#include <vector>

#include "vb/engine/convex_shape.h"
#include "vb/terrain/obstacle_field.h"
#include "vb/terrain/terrain.h"

namespace vb::terrain {

// One contact of a moving body with the static world, for the next physics step.
struct BodyContact {
  Vec3 point_W = Vec3::Zero();    // on the body's surface
  Vec3 normal_W = Vec3::UnitZ();  // unit: the direction the contact pushes the body
  double depth_m = 0.0;           // penetration, >= 0
  double friction = 0.8;          // Coulomb coefficient of the pair
  int obstacle_tag = -1;          // -1: the ground; rocks i, trees kTreeTagOffset + j
};

// Friction of a body (not a tire) sliding on deformable ground, whose patches carry no Coulomb
// coefficient: tan 26.6 deg, within the soils' internal friction angles (mud 20-30 deg, sand
// ~30 deg, snow ~20 deg: reference_vehicle_soil.md §2.5).
constexpr double kBodyOnSoilFriction = 0.5;

// Scratch buffers reused between calls (no allocation once sized).
struct ContactScratch {
  std::vector<BodyContact> candidates;
  std::vector<int> obstacles;
  std::vector<char> taken;
  std::vector<Vec3> face_points;     // WheelObstacleContacts: the cylinder's deepest point per face
  std::vector<double> face_depths;   // and its signed distance to that face's plane
};

// Shapes further apart than this along one of their face normals touch nowhere: the contact
// queries skip such a pair before their sample tests. Far above the rounding of posed shapes, so
// a skipped pair is one the full tests would have found no contact in.
constexpr double kSeparatedBy_m = 1e-6;
// A body sample further than this outside an obstacle's box (in the body's frame) is not posed:
// far above the rounding of posing it, so it is one the world-frame box test would have dropped.
constexpr double kPoseMargin_m = 1e-6;

// The highest the ground gets under the box [lo, hi] (grid vertices in its footprint and the
// surface at its centre): a body entirely above it cannot touch the ground.
double MaxGroundHeightUnder(const Vec3& lo, const Vec3& hi, const Terrain& ground);

// True when, over the footprint of `body_W` (a convex piece posed in the world), every ground
// vertex lies beyond the plane of the piece's lowest face (by a rounding margin): the triangulated
// ground is then entirely outside the piece and GroundContacts would find nothing. Much tighter
// than MaxGroundHeightUnder for a body tilted with the slope under it (the common case on rough
// worlds); conservative: false whenever unsure (a lowest face not facing down, a footprint that
// leaves the grid).
bool GroundBeyondLowestFace(const engine::ConvexShape& body_W, const Terrain& ground);

// Appends to *out at most max_contacts contacts of `body_W` (a convex piece posed in the world)
// with the ground; body_friction combines with the patch's by the minimum.
void GroundContacts(const engine::ConvexShape& body_W, const Terrain& ground, double body_friction,
                    int max_contacts, ContactScratch* scratch, std::vector<BodyContact>* out);
// The same for a caller that has MaxGroundHeightUnder(body_W.aabb_min, body_W.aabb_max, ground)
// already (its quick reject): `max_ground_h_m` must be that value.
void GroundContacts(const engine::ConvexShape& body_W, const Terrain& ground,
                    double max_ground_h_m, double body_friction, int max_contacts,
                    ContactScratch* scratch, std::vector<BodyContact>* out);
// The same with the samples still in the piece's own frame: `body_W` is the piece posed by
// `pose` without its samples (ConvexShape::TransformInto with_samples = false), `samples_B` the
// unposed piece's samples. Each sample's height is computed first and the sample posed only if it
// is below max_ground_h_m; the result is bit for bit that of posing every sample
// (ConvexShape::TransformSamplesInto) and calling the overload above.
void GroundContacts(const engine::ConvexShape& body_W, const std::vector<Vec3>& samples_B,
                    const Pose& pose, const Terrain& ground, double max_ground_h_m,
                    double body_friction, int max_contacts, ContactScratch* scratch,
                    std::vector<BodyContact>* out);

// Appends at most max_per_obstacle contacts per touching obstacle.
void ObstacleContacts(const engine::ConvexShape& body_W, const ObstacleField& field,
                      double body_friction, int max_per_obstacle, ContactScratch* scratch,
                      std::vector<BodyContact>* out);
// The same with the body's samples given in its own frame (samples_B, posed by `pose` as
// ConvexShape::TransformSamplesInto does, only those near an obstacle); body_W's own samples
// are not read. The same contacts, bit for bit, as posing them all first.
void ObstacleContacts(const engine::ConvexShape& body_W, const std::vector<Vec3>& samples_B,
                      const Pose& pose, const ObstacleField& field, double body_friction,
                      int max_per_obstacle, ContactScratch* scratch,
                      std::vector<BodyContact>* out);

// Whether ObstacleContacts(body_W, field, ...) can find a contact: an obstacle whose box overlaps
// the body's and that no face of either separates from the other (ObstacleContacts' first test).
// It reads the body's vertices, faces and box only, so the caller can pose the body's samples
// after it says yes.
bool MayTouchAnObstacle(const engine::ConvexShape& body_W, const ObstacleField& field,
                        ContactScratch* scratch);

// A wheel (cylinder: centre, unit spin axis, radius, half width) against the obstacles.
void WheelObstacleContacts(const Vec3& center_W, const Vec3& axis_W, double radius_m,
                           double half_width_m, const ObstacleField& field, double wheel_friction,
                           int max_per_obstacle, ContactScratch* scratch,
                           std::vector<BodyContact>* out);

// Keeps at most `max_contacts` of `candidates` in *out (appended): the deepest first, then
// repeatedly the one farthest from those kept (a well-spread support). Deterministic.
void ReduceContacts(const std::vector<BodyContact>& candidates, int max_contacts,
                    std::vector<char>* taken, std::vector<BodyContact>* out);

}  // namespace vb::terrain
