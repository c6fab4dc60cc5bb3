// vb's own articulated-body dynamics behind the physics adapter (physics_world.h): the default
// implementation (CMake VB_PHYSICS=vb; =bullet links the Bullet adapter instead; issue 24). Same
// interface, same model: a floating base with a tree of single-DoF links, joint limits, implicit
// joint motors and vb's contacts as implicit constraints; semi-implicit Euler at one fixed step.
//
// Why: Bullet's generic multibody code (its articulated-body algorithm over spatial transforms and
// a row-by-row Jacobian set-up through the same machinery) was ~60 % of the rigid-world step. A
// vehicle has ~14 degrees of freedom, so the joint-space form is small and dense:
//   1. kinematics of every link (world rotation, COM, joint pivot and axis);
//   2. the mass matrix M = sum_i J_i^T D_i J_i (J_i: the link's COM and angular velocity as
//      columns of the generalised velocities, non-zero only for the base and the link's
//      ancestors; D_i = diag(m_i, I_i)) and the generalised forces h (gravity, applied forces,
//      joint forces, minus the velocity-product terms: centripetal, Coriolis, gyroscopic);
//   3. u* = u + dt M^-1 h (Cholesky of M);
//   4. constraint rows j (contacts: normal and friction; joint limits; motors) with the response
//      y = M^-1 j^T, solved by projected Gauss-Seidel on impulses as Bullet's sequential-impulse
//      solver does (the same order: joint rows, contact normals, friction; the same Baumgarte
//      factor 0.2, the same stop on a converged sweep), u = u* + sum y lambda;
//   5. positions from the new velocities (base rotation by the exponential map).
//
// Difference from Bullet on purpose: a contact has friction in both tangent directions, bounded
// together by the Coulomb cone (Bullet's multibody solver, in its default mode, gives a contact one
// friction direction only, a fixed tangent from the normal: a chassis on flat ground resists
// sliding along world y but not x, and a wheel against a vertical rock face gets no vertical
// friction). kFrictionDirections = 1 reproduces Bullet's single direction for comparison.
#include "vb/engine/physics_world.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vb/engine/error.h"

namespace vb::engine {
namespace {

constexpr int kMaxDof = 32;            // 6 for the base + joint DoFs; vehicles use <= 14
constexpr double kContactErp = 0.2;    // penetration removed per step (Bullet's m_erp2 default)
constexpr double kLimitErp = 0.2;      // joint limits beyond the limit (Bullet's m_erp2 default)
constexpr int kIterations = 30;        // sweeps at most
constexpr double kResidual = 1e-12;    // stop once no row's velocity changes by > 1 um/s
constexpr int kFrictionDirections = 2;

// A joint's implicit motor (persistent until changed).
enum class MotorMode { kNone, kVelocity, kPosition };

// One constraint row of one body: lambda is an impulse along j (generalised velocities).
struct Row {
  // User-provided, so that emplace_back() does not zero the arrays first (value-initialisation
  // would: ~600 bytes per row); only the entries a row sets are read.
  Row() {}
  double j[kMaxDof];  // zero except at nz[0 .. nnz)
  int nz[kMaxDof];
  int nnz = 0;
  bool ready = true;     // y, inv_diag and rhs computed (joint rows: once they act)
  double target = 0.0;   // joint rows: the target velocity along j
  double y[kMaxDof];  // M^-1 j^T
  double inv_diag = 0.0;  // 1 / (j M^-1 j^T), 0 for a degenerate row
  double rhs = 0.0;       // (target velocity - j u*) * inv_diag
  double lo = 0.0, hi = 0.0;
  double lambda = 0.0;
  double mu = 0.0;        // friction rows: the coefficient; their bounds follow the normal's impulse
  int normal = -1;        // friction rows: index of their normal row
  int pair = -1;          // the first of two friction rows: index of the second
};

// Bullet's btPlaneSpace1: a tangent basis of the normal n (unit). vb uses the same tangents so
// that kFrictionDirections = 1 is Bullet's friction.
void PlaneSpace(const Vec3& n, Vec3* p, Vec3* q) {
  if (std::abs(n.z()) > 0.7071067811865475244) {
    const double a = n.y() * n.y() + n.z() * n.z();
    const double k = 1.0 / std::sqrt(a);
    *p = Vec3(0.0, -n.z() * k, n.y() * k);
    *q = Vec3(a * k, -n.x() * p->z(), n.x() * p->y());
  } else {
    const double a = n.x() * n.x() + n.y() * n.y();
    const double k = 1.0 / std::sqrt(a);
    *p = Vec3(-n.y() * k, n.x() * k, 0.0);
    *q = Vec3(-n.z() * p->y(), n.z() * p->x(), a * k);
  }
}

}  // namespace

struct PhysicsWorld::Impl {
  struct Link {
    // model
    int parent = -1;
    JointType joint = JointType::kRevolute;
    Vec3 axis_P = Vec3::UnitY();
    Vec3 e_P = Vec3::Zero();  // parent COM to joint pivot, parent frame
    Vec3 d_L = Vec3::Zero();  // pivot to this COM, this frame
    double mass_kg = 1.0;
    Vec3 inertia = Vec3::Ones();
    bool has_limit = false;
    double lower = 0.0, upper = 0.0;
    int dof = -1;              // index in the generalised velocities, -1 for a prescribed joint
    std::vector<int> chain;    // links with a DoF from the base down to this one (inclusive)
    // state
    double q = 0.0, qdot = 0.0;
    MotorMode motor = MotorMode::kNone;
    double motor_target_v = 0.0, motor_target_q = 0.0, motor_max_force = 0.0;
    // forces for the next step
    Vec3 force_W = Vec3::Zero(), torque_W = Vec3::Zero();
    double joint_force = 0.0;
    // kinematics of the current state (world)
    Quat rot = Quat::Identity();
    Mat3 R = Mat3::Identity();
    Vec3 p = Vec3::Zero();      // COM
    Vec3 pivot = Vec3::Zero();
    Vec3 axis_W = Vec3::UnitY();
    Pose pose;                  // p and rot as the read-out gives them
    bool moved = false;         // its joint angle changed since its kinematics were computed
    // read-out velocities (prescribed rates included), world frame
    Vec3 w_ro = Vec3::Zero(), v_ro = Vec3::Zero();
    // scratch of the step: velocities without prescribed rates, bias accelerations
    Vec3 w = Vec3::Zero(), v = Vec3::Zero(), alpha = Vec3::Zero(), acc = Vec3::Zero();
  };
  struct Body {
    double mass_kg = 1.0;
    Vec3 inertia = Vec3::Ones();
    Vec3 pos = Vec3::Zero();
    Quat rot = Quat::Identity();  // base to world
    Vec3 vel = Vec3::Zero(), omega = Vec3::Zero();
    Vec3 force_W = Vec3::Zero(), torque_W = Vec3::Zero();
    std::vector<Link> links;
    int n = 6;  // generalised velocities
    // kinematics to recompute: some link's (kin_stale), every link's (base_moved; else only the
    // links marked `moved` and their descendants: a steering angle moves its knuckle and wheel)
    mutable bool kin_stale = true, vel_stale = true, base_moved = true;
    mutable Mat3 R = Mat3::Identity();
    bool any_prescribed_rate = false;
    // scratch of the step
    // n x n, column-major: the mass matrix, overwritten by its Cholesky factor L (lower)
    double M[kMaxDof * kMaxDof];
    double h[kMaxDof], u[kMaxDof], du[kMaxDof];
    std::vector<Row> rows;       // joint rows first, then per contact a normal and its friction
    std::vector<int> joint_rows, normal_rows, friction_rows;
  };
  std::vector<Body> bodies;
  Vec3 gravity = Vec3(0.0, 0.0, -kGravity);
  std::vector<ContactConstraint> pending_contacts;
  std::vector<ObstacleContact> pending_touches;
  std::vector<ObstacleContact> contacts;
  std::vector<const ContactConstraint*> body_contacts;  // scratch of Step

  Body& Get(MultiBodyId id) {
    VB_DEMAND(id >= 0 && id < static_cast<int>(bodies.size()));
    return bodies[static_cast<size_t>(id)];
  }
  const Body& Get(MultiBodyId id) const {
    VB_DEMAND(id >= 0 && id < static_cast<int>(bodies.size()));
    return bodies[static_cast<size_t>(id)];
  }
  static Link& LinkOf(Body& b, int link) {
    VB_DEMAND(link >= 0 && link < static_cast<int>(b.links.size()));
    return b.links[static_cast<size_t>(link)];
  }
  static const Link& LinkOf(const Body& b, int link) {
    VB_DEMAND(link >= 0 && link < static_cast<int>(b.links.size()));
    return b.links[static_cast<size_t>(link)];
  }

  // Link rotations, COMs, pivots and axes from the base pose and the joint coordinates.
  // Links whose inputs did not change keep their values: recomputing them would give the same.
  static void Kinematics(const Body& cb) {
    if (!cb.kin_stale) return;
    Body& b = const_cast<Body&>(cb);
    const bool all = b.base_moved;
    if (all) b.R = b.rot.toRotationMatrix();
    for (Link& l : b.links) {
      const bool base_parent = l.parent < 0;
      if (!all && !l.moved && (base_parent || !b.links[static_cast<size_t>(l.parent)].moved))
        continue;
      l.moved = true;  // its descendants follow
      const Quat& rot_p = base_parent ? b.rot : b.links[static_cast<size_t>(l.parent)].rot;
      const Mat3& R_p = base_parent ? b.R : b.links[static_cast<size_t>(l.parent)].R;
      const Vec3& p_p = base_parent ? b.pos : b.links[static_cast<size_t>(l.parent)].p;
      l.axis_W = R_p * l.axis_P;
      if (l.joint == JointType::kPrismatic) {
        l.rot = rot_p;
        l.R = R_p;
        l.pivot = p_p + R_p * (l.e_P + l.q * l.axis_P);
      } else {
        l.rot = rot_p * Quat(Eigen::AngleAxisd(l.q, l.axis_P));
        l.R = l.rot.toRotationMatrix();
        l.pivot = p_p + R_p * l.e_P;
      }
      l.p = l.pivot + l.R * l.d_L;
      l.pose.position = l.p;
      l.pose.rotation = l.rot.normalized();
    }
    for (Link& l : b.links) l.moved = false;
    b.kin_stale = b.base_moved = false;
    b.vel_stale = true;
  }

  // Velocities of every link from the base's and the joint rates. With `prescribed` the
  // prescribed joints' rates count (read-out), without they do not (dynamics: a prescribed joint
  // adds no momentum, as physics_world.h says).
  static void LinkVelocities(Body& b, bool prescribed) {
    for (Link& l : b.links) {
      const bool base_parent = l.parent < 0;
      const Vec3& w_p = base_parent ? b.omega
                                    : (prescribed ? b.links[static_cast<size_t>(l.parent)].w_ro
                                                  : b.links[static_cast<size_t>(l.parent)].w);
      const Vec3& v_p = base_parent ? b.vel
                                    : (prescribed ? b.links[static_cast<size_t>(l.parent)].v_ro
                                                  : b.links[static_cast<size_t>(l.parent)].v);
      const Vec3& p_p = base_parent ? b.pos : b.links[static_cast<size_t>(l.parent)].p;
      Vec3& w = prescribed ? l.w_ro : l.w;
      Vec3& v = prescribed ? l.v_ro : l.v;
      if (l.joint == JointType::kPrismatic) {
        w = w_p;
        v = v_p + w_p.cross(l.p - p_p) + l.axis_W * l.qdot;
      } else {
        const double rate =
            l.joint == JointType::kRevolute ? l.qdot : (prescribed ? l.qdot : 0.0);
        w = w_p + l.axis_W * rate;
        v = v_p + w_p.cross(l.pivot - p_p) + w.cross(l.p - l.pivot);
      }
    }
  }

  static void ReadOutVelocities(const Body& cb) {
    Kinematics(cb);
    if (!cb.vel_stale) return;
    Body& b = const_cast<Body&>(cb);
    LinkVelocities(b, /*prescribed=*/true);
    b.vel_stale = false;
  }

  void StepBody(Body& b, double dt, const std::vector<const ContactConstraint*>& contacts);
};

namespace {

// In place: the lower triangle of A (column-major n x n) becomes L with A = L L^T (column by
// column, each column's update of the later ones contiguous). False if A is not positive definite.
bool Cholesky(int n, double* A) {
  for (int k = 0; k < n; ++k) {
    double* ck = A + k * n;
    if (!(ck[k] > 0.0)) return false;
    const double d = std::sqrt(ck[k]);
    ck[k] = d;
    const double inv = 1.0 / d;
    for (int i = k + 1; i < n; ++i) ck[i] *= inv;
    for (int j = k + 1; j < n; ++j) {
      double* cj = A + j * n;
      const double ljk = ck[j];
      for (int i = j; i < n; ++i) cj[i] -= ck[i] * ljk;
    }
  }
  return true;
}

// x = (L L^T)^-1 x, L from Cholesky.
void CholeskySolve(int n, const double* L, double* x) {
  for (int p = 0; p < n; ++p) {  // L z = x, by columns
    const double* cp = L + p * n;
    const double xp = x[p] / cp[p];
    x[p] = xp;
    for (int i = p + 1; i < n; ++i) x[i] -= cp[i] * xp;
  }
  for (int i = n - 1; i >= 0; --i) {  // L^T x = z, by rows of L^T (columns of L)
    const double* ci = L + i * n;
    double s = x[i];
    for (int p = i + 1; p < n; ++p) s -= ci[p] * x[p];
    x[i] = s / ci[i];
  }
}

}  // namespace

void PhysicsWorld::Impl::StepBody(Body& b, double dt,
                                  const std::vector<const ContactConstraint*>& body_contacts) {
  Kinematics(b);
  const int n = b.n;
  // velocities (without prescribed rates) and bias accelerations (u' = 0), down the tree
  const Vec3 zero = Vec3::Zero();
  LinkVelocities(b, /*prescribed=*/false);
  for (Link& l : b.links) {
    const bool base_parent = l.parent < 0;
    const Link* par = base_parent ? nullptr : &b.links[static_cast<size_t>(l.parent)];
    const Vec3& w_p = base_parent ? b.omega : par->w;
    const Vec3& al_p = base_parent ? zero : par->alpha;
    const Vec3& a_p = base_parent ? zero : par->acc;
    const Vec3& p_p = base_parent ? b.pos : par->p;
    if (l.joint == JointType::kPrismatic) {
      const Vec3 r = l.p - p_p;
      l.alpha = al_p;
      l.acc = a_p + al_p.cross(r) + w_p.cross(w_p.cross(r)) + 2.0 * w_p.cross(l.axis_W * l.qdot);
    } else {
      const double rate = l.joint == JointType::kRevolute ? l.qdot : 0.0;
      const Vec3 r1 = l.pivot - p_p, r2 = l.p - l.pivot;
      l.alpha = al_p + w_p.cross(l.axis_W * rate);
      l.acc = a_p + al_p.cross(r1) + w_p.cross(w_p.cross(r1)) + l.alpha.cross(r2) +
              l.w.cross(l.w.cross(r2));
    }
  }

  // Mass matrix (lower triangle) and generalised forces, from each body's share of the kinetic
  // energy: with r the body's COM from the base's, its velocity is v_b - [r]x w_b + sum jv q' and
  // its angular velocity w_b + sum jw q' (the sums over the DoFs of its chain), so
  //   M(v_b, v_b) = m, M(w_b, v_b) = m [r]x, M(w_b, w_b) = m (|r|^2 - r r^T) + I,
  //   M(v_b, q) = m jv, M(w_b, q) = m r x jv + I jw, M(q, q') = m jv.jv' + jw.I jw',
  // and h = J^T (f, tau) with f, tau the net force and torque about the COM less m a_bias,
  // I alpha_bias + w x I w.
  double* M = b.M;
  double* h = b.h;
  std::fill(M, M + n * n, 0.0);
  std::fill(h, h + n, 0.0);
  double m_total = 0.0;
  Vec3 m_r = Vec3::Zero(), f_total = Vec3::Zero(), tau_total = Vec3::Zero();
  Mat3 I_bb = Mat3::Zero();
  {
    const Mat3 I_W = b.R * b.inertia.asDiagonal() * b.R.transpose();
    m_total += b.mass_kg;
    I_bb += I_W;
    f_total += b.force_W + b.mass_kg * gravity;
    tau_total += b.torque_W - b.omega.cross(I_W * b.omega);
  }
  Vec3 jv[kMaxDof], jw[kMaxDof], m_jv[kMaxDof], I_jw[kMaxDof];
  for (const Link& l : b.links) {
    const double m = l.mass_kg;
    const Vec3 r = l.p - b.pos;
    const Mat3 I_W = l.R * l.inertia.asDiagonal() * l.R.transpose();
    const Vec3 f = l.force_W + m * gravity - m * l.acc;
    const Vec3 tau = l.torque_W - I_W * l.alpha - l.w.cross(I_W * l.w);
    m_total += m;
    m_r += m * r;
    I_bb += m * (r.squaredNorm() * Mat3::Identity() - r * r.transpose()) + I_W;
    f_total += f;
    tau_total += r.cross(f) + tau;
    const int c = static_cast<int>(l.chain.size());
    for (int k = 0; k < c; ++k) {
      const Link& anc = b.links[static_cast<size_t>(l.chain[static_cast<size_t>(k)])];
      if (anc.joint == JointType::kPrismatic) {
        jv[k] = anc.axis_W;
        jw[k].setZero();
      } else {
        jv[k] = anc.axis_W.cross(l.p - anc.pivot);
        jw[k] = anc.axis_W;
      }
      m_jv[k] = m * jv[k];
      I_jw[k] = I_W * jw[k];
      const int dk = anc.dof;
      const Vec3 ang = r.cross(m_jv[k]) + I_jw[k];
      for (int i = 0; i < 3; ++i) {
        M[i * n + dk] += m_jv[k](i);
        M[(3 + i) * n + dk] += ang(i);
      }
      h[dk] += jv[k].dot(f) + jw[k].dot(tau);
      for (int q = 0; q <= k; ++q) {
        const int dq = b.links[static_cast<size_t>(l.chain[static_cast<size_t>(q)])].dof;
        // dq <= dk (a parent's DoF comes first): column dq, row dk
        M[dq * n + dk] += m_jv[k].dot(jv[q]) + jw[q].dot(I_jw[k]);
      }
    }
    if (l.dof >= 0) h[l.dof] += l.joint_force;
  }
  for (int i = 0; i < 3; ++i) {
    M[i * n + i] = m_total;
    h[i] = f_total(i);
    h[3 + i] = tau_total(i);
    for (int j = 0; j <= i; ++j) M[(3 + j) * n + 3 + i] = I_bb(i, j);
  }
  // M(w_b, v_b) = [m r]x: rows 3-5, columns 0-2
  M[0 * n + 4] = m_r.z();
  M[0 * n + 5] = -m_r.y();
  M[1 * n + 3] = -m_r.z();
  M[1 * n + 5] = m_r.x();
  M[2 * n + 3] = m_r.y();
  M[2 * n + 4] = -m_r.x();

  // M^-1 (the rows' responses are its columns' combinations) and the unconstrained velocities
  double* u = b.u;
  u[0] = b.vel.x();
  u[1] = b.vel.y();
  u[2] = b.vel.z();
  u[3] = b.omega.x();
  u[4] = b.omega.y();
  u[5] = b.omega.z();
  for (const Link& l : b.links)
    if (l.dof >= 0) u[l.dof] = l.qdot;
  if (!Cholesky(n, b.M)) {
    // not positive definite: no finite answer; the trial ends on the non-finite state
    b.vel.setConstant(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  CholeskySolve(n, M, h);
  for (int i = 0; i < n; ++i) u[i] += dt * h[i];

  // constraint rows
  b.rows.clear();
  b.joint_rows.clear();
  b.normal_rows.clear();
  b.friction_rows.clear();
  // y = M^-1 j^T over j's non-zeros, the diagonal j y and the right-hand side
  auto finish_row = [&](Row& row, double target_velocity) {
    std::fill(row.y, row.y + n, 0.0);
    double v0 = 0.0;
    for (int a = 0; a < row.nnz; ++a) {
      const int k = row.nz[a];
      row.y[k] = row.j[k];
      v0 += row.j[k] * u[k];
    }
    CholeskySolve(n, M, row.y);
    row.ready = true;
    double diag = 0.0;
    for (int a = 0; a < row.nnz; ++a) diag += row.j[row.nz[a]] * row.y[row.nz[a]];
    row.inv_diag = diag > 1e-12 ? 1.0 / diag : 0.0;
    row.rhs = (target_velocity - v0) * row.inv_diag;
    row.lambda = 0.0;
  };
  auto joint_row = [&](const Link& l, double sign, double target, double lo, double hi) {
    b.rows.emplace_back();
    Row& row = b.rows.back();
    row.j[l.dof] = sign;
    row.nz[0] = l.dof;
    row.nnz = 1;
    row.lo = lo;
    row.hi = hi;
    row.target = target;
    row.ready = false;  // its response is computed once it acts (most limits never do)
    b.joint_rows.push_back(static_cast<int>(b.rows.size()) - 1);
  };
  for (const Link& l : b.links) {
    if (l.dof < 0) continue;
    if (l.has_limit) {
      // lower: q - lower >= 0; upper: upper - q >= 0. Approaching within the step is free;
      // beyond the limit, a share of the error is removed per step. The rows are lazy: their
      // response is computed only once one acts (solve_row), which most never do.
      const double d_lo = l.q - l.lower, d_hi = l.upper - l.q;
      joint_row(l, 1.0, d_lo > 0 ? -d_lo / dt : -d_lo * kLimitErp / dt, 0.0, 1e30);
      joint_row(l, -1.0, d_hi > 0 ? -d_hi / dt : -d_hi * kLimitErp / dt, 0.0, 1e30);
    }
    if (l.motor != MotorMode::kNone && l.motor_max_force > 0.0) {
      const double impulse = l.motor_max_force * dt;
      const double target = l.motor == MotorMode::kPosition
                                ? 0.2 * (l.motor_target_q - l.q) / dt
                                : l.motor_target_v;
      joint_row(l, 1.0, target, -impulse, impulse);
    }
  }
  for (const ContactConstraint* c : body_contacts) {
    // the generalised row of a direction d at the contact point of the contact's link
    const std::vector<int>* chain =
        c->link >= 0 ? &b.links[static_cast<size_t>(c->link)].chain : nullptr;
    auto fill = [&](Row& row, const Vec3& d) {
      const Vec3 x = c->point_W;
      const Vec3 m = (x - b.pos).cross(d);
      row.j[0] = d.x();
      row.j[1] = d.y();
      row.j[2] = d.z();
      row.j[3] = m.x();
      row.j[4] = m.y();
      row.j[5] = m.z();
      for (int k = 0; k < 6; ++k) row.nz[k] = k;
      row.nnz = 6;
      if (chain != nullptr) {
        for (int a : *chain) {
          const Link& anc = b.links[static_cast<size_t>(a)];
          row.j[anc.dof] = anc.joint == JointType::kPrismatic
                               ? anc.axis_W.dot(d)
                               : anc.axis_W.dot((x - anc.pivot).cross(d));
          row.nz[row.nnz++] = anc.dof;
        }
      }
    };
    b.rows.emplace_back();
    const int ni = static_cast<int>(b.rows.size()) - 1;
    {
      Row& row = b.rows.back();
      fill(row, c->normal_W);
      row.lo = 0.0;
      row.hi = 1e30;
      finish_row(row, c->depth_m * kContactErp / dt);
      b.normal_rows.push_back(ni);
    }
    Vec3 t1, t2;
    PlaneSpace(c->normal_W, &t1, &t2);
    for (int k = 0; k < kFrictionDirections; ++k) {
      b.rows.emplace_back();
      Row& row = b.rows.back();
      fill(row, k == 0 ? t1 : t2);
      row.mu = c->friction;
      row.normal = ni;
      row.pair = -1;
      finish_row(row, 0.0);
      b.friction_rows.push_back(static_cast<int>(b.rows.size()) - 1);
    }
    if (kFrictionDirections == 2)
      b.rows[static_cast<size_t>(b.friction_rows[b.friction_rows.size() - 2])].pair =
          b.friction_rows.back();
  }

  // projected Gauss-Seidel on the impulses; du = sum y lambda
  double* du = b.du;
  std::fill(du, du + n, 0.0);
  auto velocity_term = [&](const Row& row) {
    double s = 0.0;
    for (int a = 0; a < row.nnz; ++a) s += row.j[row.nz[a]] * du[row.nz[a]];
    return s;
  };
  auto apply = [&](const Row& row, double delta) {
    for (int k = 0; k < n; ++k) du[k] += row.y[k] * delta;
  };
  auto solve_row = [&](Row& row) {
    if (!row.ready) {
      // a joint row (j = +-e_dof) whose impulse is still 0 stays 0 unless the velocity along
      // it misses its target (below it for a limit, any miss for a motor)
      const int k = row.nz[0];
      const double v = row.j[k] * (u[k] + du[k]);
      if (row.lo == 0.0 ? row.target <= v : row.target == v) return 0.0;
      finish_row(row, row.target);
    }
    if (row.inv_diag == 0.0) return 0.0;
    const double delta = row.rhs - velocity_term(row) * row.inv_diag;
    const double sum = row.lambda + delta;
    const double clamped = std::min(row.hi, std::max(row.lo, sum));
    const double applied = clamped - row.lambda;
    if (applied == 0.0) return 0.0;
    row.lambda = clamped;
    apply(row, applied);
    const double dv = applied / row.inv_diag;
    return dv * dv;
  };
  const int nj = static_cast<int>(b.joint_rows.size());
  for (int it = 0; it < kIterations && !b.rows.empty(); ++it) {
    double residual = 0.0;
    for (int k = 0; k < nj; ++k) {
      const int index = (it & 1) ? k : nj - 1 - k;
      residual = std::max(residual, solve_row(b.rows[static_cast<size_t>(b.joint_rows[index])]));
    }
    for (int r : b.normal_rows)
      residual = std::max(residual, solve_row(b.rows[static_cast<size_t>(r)]));
    for (size_t k = 0; k < b.friction_rows.size(); ++k) {
      Row& row = b.rows[static_cast<size_t>(b.friction_rows[k])];
      const double limit = row.mu * b.rows[static_cast<size_t>(row.normal)].lambda;
      if (row.pair < 0) {
        if (limit <= 0.0) continue;
        row.lo = -limit;
        row.hi = limit;
        residual = std::max(residual, solve_row(row));
        continue;
      }
      // two directions: both updates from the same velocities, then onto the cone's disc
      Row& row2 = b.rows[static_cast<size_t>(row.pair)];
      ++k;
      if (row.inv_diag == 0.0 || row2.inv_diag == 0.0) continue;
      const double d1 = row.rhs - velocity_term(row) * row.inv_diag;
      const double d2 = row2.rhs - velocity_term(row2) * row2.inv_diag;
      double s1 = row.lambda + d1, s2 = row2.lambda + d2;
      const double norm = std::sqrt(s1 * s1 + s2 * s2);
      if (norm > limit) {
        const double scale = norm > 0.0 && limit > 0.0 ? limit / norm : 0.0;
        s1 *= scale;
        s2 *= scale;
      }
      const double a1 = s1 - row.lambda, a2 = s2 - row2.lambda;
      row.lambda = s1;
      row2.lambda = s2;
      apply(row, a1);
      apply(row2, a2);
      const double dv = a1 / row.inv_diag + a2 / row2.inv_diag;
      residual = std::max(residual, dv * dv);
    }
    if (residual <= kResidual) break;
  }
  for (int k = 0; k < n; ++k) u[k] += du[k];

  // positions from the new velocities
  b.vel = Vec3(u[0], u[1], u[2]);
  b.omega = Vec3(u[3], u[4], u[5]);
  b.pos += dt * b.vel;
  const double angle = b.omega.norm() * dt;
  if (angle > 0.0) b.rot = Quat(Eigen::AngleAxisd(angle, b.omega / b.omega.norm())) * b.rot;
  b.rot.normalize();
  for (Link& l : b.links) {
    if (l.dof < 0) continue;
    l.qdot = u[l.dof];
    l.q += dt * l.qdot;
  }
  b.kin_stale = b.base_moved = true;
  b.vel_stale = true;
  b.force_W.setZero();
  b.torque_W.setZero();
  for (Link& l : b.links) {
    l.force_W.setZero();
    l.torque_W.setZero();
    l.joint_force = 0.0;
  }
}

PhysicsWorld::PhysicsWorld(double gravity_mps2) : impl_(std::make_unique<Impl>()) {
  impl_->gravity = Vec3(0.0, 0.0, -gravity_mps2);
}

PhysicsWorld::~PhysicsWorld() = default;

void PhysicsWorld::SetGravity(const Vec3& gravity_W) { impl_->gravity = gravity_W; }

Vec3 PhysicsWorld::Gravity() const { return impl_->gravity; }

MultiBodyId PhysicsWorld::AddMultiBody(const MultiBodyBaseSpec& base,
                                       const std::vector<MultiBodyLinkSpec>& links) {
  Impl::Body b;
  b.mass_kg = base.mass_kg;
  b.inertia = base.inertia_kgm2;
  b.pos = base.pose_W.position;
  b.rot = base.pose_W.rotation.normalized();
  int n = 6;
  for (size_t i = 0; i < links.size(); ++i) {
    const MultiBodyLinkSpec& s = links[i];
    VB_DEMAND(s.parent < static_cast<int>(i));
    Impl::Link l;
    l.parent = s.parent;
    l.joint = s.joint;
    l.axis_P = s.axis_P.normalized();
    l.e_P = s.parent_com_to_joint_P;
    l.d_L = s.joint_to_com_L;
    l.mass_kg = s.mass_kg;
    l.inertia = s.inertia_kgm2;
    l.has_limit = s.limit_lower <= s.limit_upper;
    if (s.joint == JointType::kPrescribedRevolute) VB_DEMAND(!l.has_limit);
    l.lower = s.limit_lower;
    l.upper = s.limit_upper;
    if (s.joint != JointType::kPrescribedRevolute) l.dof = n++;
    if (s.parent >= 0) l.chain = b.links[static_cast<size_t>(s.parent)].chain;
    if (l.dof >= 0) l.chain.push_back(static_cast<int>(i));
    b.links.push_back(std::move(l));
  }
  VB_DEMAND(n <= kMaxDof);
  b.n = n;
  b.rows.reserve(64);
  impl_->bodies.push_back(std::move(b));
  return static_cast<MultiBodyId>(impl_->bodies.size()) - 1;
}

void PhysicsWorld::SetJointPosition(MultiBodyId id, int link, double q) {
  Impl::Body& b = impl_->Get(id);
  Impl::Link& l = Impl::LinkOf(b, link);
  l.q = q;
  if (l.joint == JointType::kPrescribedRevolute) l.qdot = 0.0;
  b.kin_stale = b.base_moved = true;
}

void PhysicsWorld::SetPrescribedJoint(MultiBodyId id, int link, double q, double qdot) {
  Impl::Body& b = impl_->Get(id);
  Impl::Link& l = Impl::LinkOf(b, link);
  VB_DEMAND(l.joint == JointType::kPrescribedRevolute);
  if (q == l.q && qdot == l.qdot) return;
  if (q != l.q) b.kin_stale = l.moved = true;
  l.q = q;
  l.qdot = qdot;
  b.vel_stale = true;
}

void PhysicsWorld::ApplyLinkForce(MultiBodyId id, int link, const Vec3& force_W,
                                  const Vec3& point_W) {
  Impl::Body& b = impl_->Get(id);
  Impl::Kinematics(b);
  Impl::Link& l = Impl::LinkOf(b, link);
  l.force_W += force_W;
  l.torque_W += (point_W - l.p).cross(force_W);
}

void PhysicsWorld::ApplyBaseForce(MultiBodyId id, const Vec3& force_W, const Vec3& point_W) {
  Impl::Body& b = impl_->Get(id);
  b.force_W += force_W;
  b.torque_W += (point_W - b.pos).cross(force_W);
}

void PhysicsWorld::ApplyLinkTorque(MultiBodyId id, int link, const Vec3& torque_W) {
  Impl::Body& b = impl_->Get(id);
  Impl::LinkOf(b, link).torque_W += torque_W;
}

void PhysicsWorld::ApplyBaseTorque(MultiBodyId id, const Vec3& torque_W) {
  impl_->Get(id).torque_W += torque_W;
}

void PhysicsWorld::AddJointForce(MultiBodyId id, int link, double force) {
  Impl::Body& b = impl_->Get(id);
  Impl::LinkOf(b, link).joint_force += force;
}

void PhysicsWorld::SetJointVelocityMotor(MultiBodyId id, int link, double target_velocity,
                                         double max_force) {
  Impl::Body& b = impl_->Get(id);
  Impl::Link& l = Impl::LinkOf(b, link);
  VB_DEMAND(l.dof >= 0);
  l.motor = MotorMode::kVelocity;
  l.motor_target_v = target_velocity;
  l.motor_max_force = std::max(0.0, max_force);
}

void PhysicsWorld::SetJointPositionMotor(MultiBodyId id, int link, double target_q,
                                         double max_force) {
  Impl::Body& b = impl_->Get(id);
  Impl::Link& l = Impl::LinkOf(b, link);
  VB_DEMAND(l.dof >= 0);
  l.motor = MotorMode::kPosition;
  l.motor_target_q = target_q;
  l.motor_target_v = 0.0;
  l.motor_max_force = std::max(0.0, max_force);
}

Pose PhysicsWorld::BasePose(MultiBodyId id) const {
  const Impl::Body& b = impl_->Get(id);
  Pose p;
  p.position = b.pos;
  p.rotation = b.rot;
  return p;
}

Vec3 PhysicsWorld::BaseLinearVelocity(MultiBodyId id) const { return impl_->Get(id).vel; }

Vec3 PhysicsWorld::BaseAngularVelocity(MultiBodyId id) const { return impl_->Get(id).omega; }

Pose PhysicsWorld::LinkPose(MultiBodyId id, int link) const {
  const Impl::Body& b = impl_->Get(id);
  Impl::Kinematics(b);
  return Impl::LinkOf(b, link).pose;
}

Vec3 PhysicsWorld::LinkPointVelocity(MultiBodyId id, int link, const Vec3& point_W) const {
  const Impl::Body& b = impl_->Get(id);
  Impl::ReadOutVelocities(b);
  const Impl::Link& l = Impl::LinkOf(b, link);
  return l.v_ro + l.w_ro.cross(point_W - l.p);
}

Vec3 PhysicsWorld::LinkAngularVelocity(MultiBodyId id, int link) const {
  const Impl::Body& b = impl_->Get(id);
  Impl::ReadOutVelocities(b);
  return Impl::LinkOf(b, link).w_ro;
}

double PhysicsWorld::JointPosition(MultiBodyId id, int link) const {
  const Impl::Body& b = impl_->Get(id);
  return Impl::LinkOf(b, link).q;
}

double PhysicsWorld::JointVelocity(MultiBodyId id, int link) const {
  const Impl::Body& b = impl_->Get(id);
  return Impl::LinkOf(b, link).qdot;
}

void PhysicsWorld::AddContact(const ContactConstraint& contact) {
  impl_->pending_contacts.push_back(contact);
}

void PhysicsWorld::ReportObstacleTouch(MultiBodyId body, int obstacle_tag) {
  VB_DEMAND(obstacle_tag >= 0);
  impl_->Get(body);
  impl_->pending_touches.push_back({body, obstacle_tag});
}

void PhysicsWorld::Step(double dt) {
  Impl& m = *impl_;
  m.contacts.clear();
  std::vector<const ContactConstraint*>& body_contacts = m.body_contacts;
  for (size_t id = 0; id < m.bodies.size(); ++id) {
    body_contacts.clear();
    for (const ContactConstraint& c : m.pending_contacts) {
      if (c.body != static_cast<int>(id)) continue;
      VB_DEMAND(c.link >= -1 && c.link < static_cast<int>(m.bodies[id].links.size()));
      body_contacts.push_back(&c);
    }
    m.StepBody(m.bodies[id], dt, body_contacts);
  }
  for (const ContactConstraint& c : m.pending_contacts) {
    VB_DEMAND(c.body >= 0 && c.body < static_cast<int>(m.bodies.size()));
    if (c.obstacle_tag >= 0) m.contacts.push_back({c.body, c.obstacle_tag});
  }
  m.pending_contacts.clear();
  for (const ObstacleContact& t : m.pending_touches) m.contacts.push_back(t);
  m.pending_touches.clear();
  SortObstacleContacts(&m.contacts);
}

const std::vector<ObstacleContact>& PhysicsWorld::ObstacleContacts() const {
  return impl_->contacts;
}

MultiBodyState PhysicsWorld::GetState(MultiBodyId id) const {
  const Impl::Body& b = impl_->Get(id);
  MultiBodyState s;
  s.base_position_W = b.pos;
  s.base_rotation = b.rot.conjugate();  // world to base, as the Bullet adapter stores it
  s.base_velocity_W = b.vel;
  s.base_angular_velocity_W = b.omega;
  s.q.resize(b.links.size());
  s.qdot.resize(b.links.size());
  for (size_t i = 0; i < b.links.size(); ++i) {
    s.q[i] = b.links[i].q;
    s.qdot[i] = b.links[i].qdot;
  }
  return s;
}

void PhysicsWorld::SetState(MultiBodyId id, const MultiBodyState& s) {
  Impl::Body& b = impl_->Get(id);
  VB_DEMAND(s.q.size() == b.links.size() && s.qdot.size() == s.q.size());
  b.pos = s.base_position_W;
  b.rot = s.base_rotation.conjugate();
  b.vel = s.base_velocity_W;
  b.omega = s.base_angular_velocity_W;
  for (size_t i = 0; i < b.links.size(); ++i) {
    b.links[i].q = s.q[i];
    b.links[i].qdot = s.qdot[i];
  }
  b.force_W.setZero();
  b.torque_W.setZero();
  for (Impl::Link& l : b.links) {
    l.force_W.setZero();
    l.torque_W.setZero();
    l.joint_force = 0.0;
  }
  b.kin_stale = b.base_moved = true;
  b.vel_stale = true;
}

bool PhysicsWorld::StateIsFinite() const {
  for (const Impl::Body& b : impl_->bodies) {
    if (!b.pos.allFinite() || !b.vel.allFinite() || !b.omega.allFinite()) return false;
    for (const Impl::Link& l : b.links)
      if (!std::isfinite(l.q) || !std::isfinite(l.qdot)) return false;
  }
  return true;
}

}  // namespace vb::engine
