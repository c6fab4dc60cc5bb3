#include "view/scene_json.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/result_io.h"
#include "vb/terrain/obstacle_field.h"
#include "vb/terrain/terrain.h"
#include "vb/terrain/terrain_physics.h"
#include "vb/vehicles/suspension_kinematics.h"

namespace vb::view {

namespace {

// Fixed-point text; -0 printed as 0 so equal worlds give equal bytes.
std::string Fixed(double x, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, x);
  std::string s = buf;
  if (s.find_first_not_of("-0.") == std::string::npos && s[0] == '-') s.erase(0, 1);
  return s;
}

std::string Xy(const Vec2& p) { return "[" + Fixed(p.x(), 3) + ", " + Fixed(p.y(), 3) + "]"; }
std::string Xyz(const Vec3& p) {
  return "[" + Fixed(p.x(), 4) + ", " + Fixed(p.y(), 4) + ", " + Fixed(p.z(), 4) + "]";
}

double MaxSteerAngle(const vehicles::VehicleParams& v) {
  if (v.steering.model == vehicles::SteeringModel::kAckermann) return v.steering.max_angle_rad;
  const double rack_max_m = v.steering.max_pinion_angle_rad * v.steering.pinion_radius_m;
  for (const vehicles::AxleParams& axle : v.axles) {
    if (!axle.steered) continue;
    const vehicles::Table1D left =
        vehicles::SteerAngleTable(axle.suspension.hardpoints, rack_max_m, 41);
    return 0.5 * (std::abs(left(rack_max_m)) + std::abs(left(-rack_max_m)));
  }
  return 0.0;
}

}  // namespace

std::string TaskSceneJson(const terrain::TaskSpec& task, double goal_radius_m) {
  std::string j = "{\"name\": " + io::JsonString(task.name);
  j += ", \"file\": " + io::JsonString(task.source_file);
  j += ", \"size_m\": [" + io::JsonNumber(task.size_x_m) + ", " + io::JsonNumber(task.size_y_m) +
       "]";
  j += ", \"scale\": " + io::JsonNumber(task.scale);
  j += ", \"goal_radius_m\": " + io::JsonNumber(goal_radius_m);

  const terrain::HeightGrid& h = task.heights;
  j += ", \"heights\": {\"rows\": " + std::to_string(h.rows) + ", \"cols\": " +
       std::to_string(h.cols) + ", \"values_m\": [";
  for (size_t i = 0; i < h.heights_m.size(); ++i) {
    if (i > 0) j += ",";
    j += Fixed(h.heights_m[i], 4);
  }
  j += "]}";

  const terrain::PatchGrid& p = task.patches;
  j += ", \"semantics\": {\"rows\": " + std::to_string(p.rows) + ", \"cols\": " +
       std::to_string(p.cols) + ", \"class_names\": [";
  for (int c = 0; c < terrain::kNumSurfaceClasses; ++c) {
    if (c > 0) j += ", ";
    j += io::JsonString(std::string(
        terrain::SurfaceClassName(static_cast<terrain::SurfaceClass>(c))));
  }
  j += "], \"classes\": [";
  for (size_t i = 0; i < p.classes.size(); ++i) {
    if (i > 0) j += ",";
    j += std::to_string(static_cast<int>(p.classes[i]));
  }
  j += "]}";

  // Obstacles exactly where the physics puts them (resting on the ground under their outline),
  // as their convex hulls (vertices and counter-clockwise face polygons), so the picture shows
  // what the vehicle hit; min_m/max_m are their bounding boxes.
  const terrain::Terrain terrain(task);
  const terrain::ObstacleField field(task, terrain);
  j += ", \"obstacles\": [";
  bool first = true;
  for (const terrain::Obstacle& o : field.obstacles()) {
    if (!first) j += ", ";
    first = false;
    const bool tree = o.tag >= terrain::kTreeTagOffset;
    j += std::string("{\"kind\": \"") + (tree ? "tree" : "rock") + "\", \"min_m\": " +
         Xyz(o.shape.aabb_min) + ", \"max_m\": " + Xyz(o.shape.aabb_max) + ", \"vertices_m\": [";
    for (size_t i = 0; i < o.shape.vertices.size(); ++i) {
      if (i > 0) j += ",";
      j += Xyz(o.shape.vertices[i]);
    }
    j += "], \"faces\": [";
    bool first_face = true;
    for (const std::vector<int>& polygon : engine::FacePolygons(o.shape)) {
      if (polygon.size() < 3) continue;
      if (!first_face) j += ",";
      first_face = false;
      j += "[";
      for (size_t i = 0; i < polygon.size(); ++i) {
        if (i > 0) j += ",";
        j += std::to_string(polygon[i]);
      }
      j += "]";
    }
    j += "]}";
  }
  j += "]";

  j += ", \"pairs\": [";
  for (size_t k = 0; k < task.pairs.size(); ++k) {
    const terrain::StartGoalPair& pair = task.pairs[k];
    if (k > 0) j += ", ";
    j += "{\"start_m\": " + Xy(pair.start_m) + ", \"goal_m\": " + Xy(pair.goal_m) +
         ", \"path_m\": [";
    for (size_t i = 0; i < pair.path_m.size(); ++i) {
      if (i > 0) j += ",";
      j += Xy(pair.path_m[i]);
    }
    j += "]}";
  }
  return j + "]}";
}

std::string VehicleSceneJson(const vehicles::VehicleParams& v) {
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (const vehicles::EnvelopePiece& piece : v.chassis.envelope) {
    for (const Vec3& q : piece.points_B) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
  std::string j = "{\"name\": " + io::JsonString(v.name);
  j += ", \"wheel_radius_m\": " + io::JsonNumber(v.wheel.radius_m);
  j += ", \"wheel_width_m\": " + io::JsonNumber(v.wheel.width_m);
  j += ", \"max_steer_rad\": " + io::JsonNumber(MaxSteerAngle(v));
  j += ", \"axles\": [";
  for (size_t i = 0; i < v.axles.size(); ++i) {
    const vehicles::AxleParams& a = v.axles[i];
    if (i > 0) j += ", ";
    j += "{\"x_m\": " + io::JsonNumber(a.x_m) + ", \"half_track_m\": " +
         io::JsonNumber(a.half_track_m) + ", \"z_m\": " + io::JsonNumber(a.z_m) +
         ", \"steered\": " + (a.steered ? "true" : "false") + "}";
  }
  j += "], \"body_min_m\": " + Xyz(lo) + ", \"body_max_m\": " + Xyz(hi) + "}";
  return j;
}

}  // namespace vb::view
