#include "vb/vehicles/suspension_kinematics.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Dense>

namespace vb::vehicles {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Upright pose: translation t of the spindle and rotation vector r about the spindle.
Vec3 Moved(const Vec3& p, const Vec3& spindle0, const Vec6& x) {
  const Vec3 r = x.tail<3>();
  const double angle = r.norm();
  const Mat3 R = angle < 1e-15 ? Mat3::Identity()
                               : Mat3(Eigen::AngleAxisd(angle, r / angle));
  return spindle0 + x.head<3>() + R * (p - spindle0);
}

Mat3 Rotation(const Vec6& x) {
  const Vec3 r = x.tail<3>();
  const double angle = r.norm();
  return angle < 1e-15 ? Mat3::Identity() : Mat3(Eigen::AngleAxisd(angle, r / angle));
}

Vec6 Residual(const DoubleWishboneHardpoints& hp, double travel_m, double rack_m, const Vec6& x) {
  const Vec3& s0 = hp.spindle;
  const Vec3 rack(0.0, rack_m, 0.0);
  Vec6 f;
  f(0) = (Moved(hp.uca_u, s0, x) - hp.uca_f).norm() - (hp.uca_u - hp.uca_f).norm();
  f(1) = (Moved(hp.uca_u, s0, x) - hp.uca_b).norm() - (hp.uca_u - hp.uca_b).norm();
  f(2) = (Moved(hp.lca_u, s0, x) - hp.lca_f).norm() - (hp.lca_u - hp.lca_f).norm();
  f(3) = (Moved(hp.lca_u, s0, x) - hp.lca_b).norm() - (hp.lca_u - hp.lca_b).norm();
  f(4) = (Moved(hp.tierod_u, s0, x) - (hp.tierod_c + rack)).norm() -
         (hp.tierod_u - hp.tierod_c).norm();
  f(5) = x(2) - travel_m;
  return f;
}


// Newton from the pose x (updated in place); false if it does not converge.
bool NewtonSolve(const DoubleWishboneHardpoints& hp, double travel_m, double rack_m, Vec6* x) {
  for (int it = 0; it < 30; ++it) {
    const Vec6 f = Residual(hp, travel_m, rack_m, *x);
    if (f.cwiseAbs().maxCoeff() < 1e-12) return true;
    Mat6 J;
    constexpr double h = 1e-7;
    for (int j = 0; j < 6; ++j) {
      Vec6 xp = *x;
      xp(j) += h;
      J.col(j) = (Residual(hp, travel_m, rack_m, xp) - f) / h;
    }
    *x -= J.fullPivLu().solve(f);
  }
  return Residual(hp, travel_m, rack_m, *x).cwiseAbs().maxCoeff() < 1e-9;
}

UprightSolution Evaluate(const DoubleWishboneHardpoints& hp, const Vec6& x) {
  UprightSolution out;
  out.ok = true;
  out.spindle = hp.spindle + x.head<3>();
  out.shock_length_m = (Moved(hp.shock_u, hp.spindle, x) - hp.shock_c).norm();
  const Vec3 axis = Rotation(x) * Vec3::UnitY();
  out.steer_angle_rad = std::atan2(-axis.x(), axis.y());
  out.camber_rad = std::asin(std::clamp(axis.z(), -1.0, 1.0));
  return out;
}

}  // namespace

UprightSolution SolveDoubleWishbone(const DoubleWishboneHardpoints& hp, double travel_m,
                                    double rack_m) {
  // Continuation in a few sub-steps keeps Newton on the physical branch for large travels.
  Vec6 x = Vec6::Zero();
  constexpr int kSubSteps = 8;
  for (int k = 1; k <= kSubSteps; ++k) {
    if (!NewtonSolve(hp, travel_m * k / kSubSteps, rack_m * k / kSubSteps, &x)) {
      return UprightSolution();
    }
  }
  return Evaluate(hp, x);
}

namespace {

// Samples the linkage at u = x0 + i dx (i < n) where u is the wheel travel (rack = false) or the
// rack travel (rack = true), by continuation outwards from the design pose (u = 0 in range): each
// Newton solve starts from its neighbour's pose. Returns the solutions or throws.
std::vector<UprightSolution> Sample(const DoubleWishboneHardpoints& hp, double x0, double dx,
                                    int n, bool rack) {
  std::vector<UprightSolution> out(n);
  const int i0 = std::clamp(static_cast<int>(std::lround(-x0 / dx)), 0, n - 1);
  for (int dir : {1, -1}) {
    Vec6 x = Vec6::Zero();
    double u_prev = 0.0;
    for (int i = i0; i >= 0 && i < n; i += dir) {
      const double u = x0 + i * dx;
      // sub-steps of at most 1 cm from the previous sample
      const int sub = std::max(1, static_cast<int>(std::ceil(std::abs(u - u_prev) / 0.01)));
      for (int k = 1; k <= sub; ++k) {
        const double uk = u_prev + (u - u_prev) * k / sub;
        if (!NewtonSolve(hp, rack ? 0.0 : uk, rack ? uk : 0.0, &x)) {
          throw std::runtime_error("double wishbone: the linkage does not assemble");
        }
      }
      u_prev = u;
      out[i] = Evaluate(hp, x);
    }
  }
  return out;
}

}  // namespace

double Table1D::operator()(double x) const {
  const double u = (x - x0) / dx;
  const int n = static_cast<int>(y.size());
  if (u <= 0.0) return y.front();
  if (u >= n - 1) return y.back();
  const int i = static_cast<int>(u);
  const double t = u - i;
  return y[i] + t * (y[i + 1] - y[i]);
}

double Table1D::Slope(double x) const {
  const int n = static_cast<int>(y.size());
  const int i = std::clamp(static_cast<int>(std::floor((x - x0) / dx)), 0, n - 2);
  return (y[i + 1] - y[i]) / dx;
}

namespace {

// Every vehicle build solves its linkages into the same tables (~19 M instructions for the HMMWV,
// a third of a gym reset); the tables are pure functions of their arguments, so a process keeps
// the last few it made and hands out copies: bit-identical to solving again.
struct TableKey {
  int kind = 0;   // 0 shock length, 1 steer angle
  std::vector<double> args;
  bool operator==(const TableKey& o) const { return kind == o.kind && args == o.args; }
};

TableKey MakeKey(int kind, const DoubleWishboneHardpoints& hp, double a, double b, int n) {
  TableKey k;
  k.kind = kind;
  for (const Vec3* p : {&hp.spindle, &hp.uca_f, &hp.uca_b, &hp.uca_u, &hp.lca_f, &hp.lca_b,
                        &hp.lca_u, &hp.shock_c, &hp.shock_u, &hp.tierod_c, &hp.tierod_u}) {
    k.args.insert(k.args.end(), {p->x(), p->y(), p->z()});
  }
  k.args.insert(k.args.end(), {a, b, static_cast<double>(n)});
  return k;
}

template <typename Make>
Table1D Memoized(const TableKey& key, Make make) {
  constexpr size_t kKept = 16;
  static std::mutex mutex;
  static std::vector<std::pair<TableKey, Table1D>> kept;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const auto& [k, t] : kept) {
      if (k == key) return t;
    }
  }
  Table1D t = make();   // may throw: nothing is kept then
  const std::lock_guard<std::mutex> lock(mutex);
  if (kept.size() == kKept) kept.erase(kept.begin());
  kept.emplace_back(key, t);
  return t;
}

}  // namespace

Table1D ShockLengthTable(const DoubleWishboneHardpoints& hp, double lo_m, double hi_m, int n) {
  return Memoized(MakeKey(0, hp, lo_m, hi_m, n), [&] {
    Table1D t;
    t.x0 = lo_m;
    t.dx = (hi_m - lo_m) / (n - 1);
    for (const UprightSolution& s : Sample(hp, t.x0, t.dx, n, false)) {
      t.y.push_back(s.shock_length_m);
    }
    return t;
  });
}

Table1D SteerAngleTable(const DoubleWishboneHardpoints& hp, double rack_max_m, int n) {
  return Memoized(MakeKey(1, hp, rack_max_m, 0.0, n), [&] {
    Table1D t;
    t.x0 = -rack_max_m;
    t.dx = 2.0 * rack_max_m / (n - 1);
    for (const UprightSolution& s : Sample(hp, t.x0, t.dx, n, true)) {
      t.y.push_back(s.steer_angle_rad);
    }
    return t;
  });
}

}  // namespace vb::vehicles
