// Tracked running gear (track_running_gear.h).
#include "vb/vehicles/track_running_gear.h"

#include <algorithm>
#include <cmath>

#include "vb/engine/error.h"

namespace vb::vehicles {

namespace {

// Implicit form of an explicit damper c on a mode of mass m (as vehicle.cc).
double ImplicitDamping(double c, double dt, double mass_kg) { return c / (1.0 + c * dt / mass_kg); }

// Joint travel limits beyond the stops (last resort only).
constexpr double kArmHardLimitBeyondStops_rad = 0.15;
constexpr double kIdlerTravel_m = 0.15;
constexpr int kMaxObstacleContactsPerWheel = 4;
// An obstacle contact is the arm's if the arm's swing moves the wheel's contact point along the
// contact normal by at least this much per radian (the wheel's lever is 0.32 m on the M113: a
// normal within ~70 degrees of the swing's direction); else the solver's, on the chassis.
constexpr double kMinArmYield_mprad = 0.1;
// Share of an obstacle contact's depth the arm removes per step (Bullet's contact error reduction
// for the chassis's contacts, btContactSolverInfo::m_erp).
constexpr double kObstacleErrorReduction = 0.2;

// d(centre)/d(angle) of a point at `d` from a revolute-y pivot, in (x, z).
Vec2 RotationRate(const Vec3& d) { return Vec2(d.z(), -d.x()); }

// `d` (in the x-z plane of the chassis) turned by q about chassis y, as a revolute-y joint at
// angle q turns its link: d/dq at 0 is RotationRate(d).
Vec3 TurnAboutY(const Vec3& d, double q) {
  const double c = std::cos(q), s = std::sin(q);
  return Vec3(c * d.x() + s * d.z(), d.y(), c * d.z() - s * d.x());
}

// Arm + road wheel: the COM on the arm between pivot and wheel centre (the arm's own COM
// halfway), from the pivot at angle 0.
Vec3 ArmComFromPivot(const TrackParams& tp) {
  const double m_aw = tp.arm_mass_kg + tp.road_wheel_mass_kg;
  return -tp.arm_pivot_offset_B * (0.5 * tp.arm_mass_kg + tp.road_wheel_mass_kg) / m_aw;
}

double RoadWheelXOf(const TrackParams& tp, int side, int k) {
  return tp.road_wheel_x_m[static_cast<size_t>(k)] +
         (side == 1 ? tp.right_road_wheel_offset_x_m : 0.0);
}

// Pivot of road-wheel arm k of `side` (0 left, +y; 1 right) in the chassis frame.
Vec3 ArmPivotOf(const TrackParams& tp, int side, int k) {
  return Vec3(RoadWheelXOf(tp, side, k), (side == 0 ? 1.0 : -1.0) * tp.half_gauge_m,
              tp.road_wheel_z_m) +
         tp.arm_pivot_offset_B;
}

}  // namespace

int ChassisArmMasses(const TrackParams& tp, LumpedMass* out) {
  const int n_rw = static_cast<int>(tp.road_wheel_x_m.size());
  VB_DEMAND(n_rw >= 2 && n_rw <= kMaxRoadWheels);
  const Vec3 com_from_pivot = ArmComFromPivot(tp);
  int n = 0;
  for (int s = 0; s < 2; ++s) {
    for (int k = 0; k < n_rw; ++k) {
      out[n].com_B = ArmPivotOf(tp, s, k) + com_from_pivot;
      out[n].mass_kg = tp.arm_mass_kg + tp.road_wheel_mass_kg;
      out[n].inertia_kgm2 = tp.arm_inertia_kgm2;
      ++n;
    }
  }
  return n;
}

TrackRunningGear::TrackRunningGear(const VehicleParams& params, const Vec3& com_B,
                                   std::vector<engine::MultiBodyLinkSpec>* links)
    : tp_(params.tracks), params_(params), com_B_(com_B) {
  n_rw_ = static_cast<int>(tp_.road_wheel_x_m.size());
  VB_DEMAND(n_rw_ >= 2 && n_rw_ <= kMaxRoadWheels);
  const double r_s = tp_.sprocket_radius_m;
  // The belt, the road wheels and the idler wheel turn with the sprocket: their kinetic energy
  // as sprocket spin inertia; the driveline's shafts as for one driven axle.
  const double rw_ratio = r_s / tp_.road_wheel_radius_m, idler_ratio = r_s / tp_.idler_radius_m;
  const double spin_inertia =
      tp_.sprocket_inertia_kgm2 + tp_.belt_mass_kg * r_s * r_s +
      n_rw_ * tp_.road_wheel_inertia_kgm2 * rw_ratio * rw_ratio +
      tp_.idler_inertia_kgm2 * idler_ratio * idler_ratio +
      DrivelineInertiaPerDrivenWheel(params.driveline, 1);
  // Arm + road wheel as one member: COM on the arm between pivot and wheel centre; its inertia
  // about the pivot axis (the damping's implicit form keeps the earlier link model's lever, the
  // pivot-to-wheel distance).
  const double m_aw = tp_.arm_mass_kg + tp_.road_wheel_mass_kg;
  const Vec3 wheel_from_pivot = -tp_.arm_pivot_offset_B;
  const Vec3 com_from_pivot = ArmComFromPivot(tp_);
  wheel_from_pivot_L_ = wheel_from_pivot;
  com_from_pivot_L_ = com_from_pivot;
  arm_mass_kg_ = m_aw;
  arm_pivot_inertia_kgm2_ = m_aw * com_from_pivot.squaredNorm() + tp_.arm_inertia_kgm2.y();
  arm_damping_inertia_kgm2_ =
      m_aw * wheel_from_pivot.squaredNorm() + tp_.arm_inertia_kgm2.y();

  for (int s = 0; s < 2; ++s) {
    Side& side = sides_[s];
    side.sign = s == 0 ? 1.0 : -1.0;
    const double y = side.sign * tp_.half_gauge_m;
    engine::MultiBodyLinkSpec sprocket;
    sprocket.parent = -1;
    sprocket.joint = engine::JointType::kRevolute;
    sprocket.axis_P = Vec3::UnitY();
    sprocket.parent_com_to_joint_P = Vec3(tp_.sprocket_B.x(), y, tp_.sprocket_B.z()) - com_B;
    sprocket.mass_kg = tp_.sprocket_mass_kg;
    sprocket.inertia_kgm2 = Vec3(1.0, spin_inertia, 1.0);
    side.sprocket_link = static_cast<int>(links->size());
    links->push_back(sprocket);
  }

  // Belt at design, per side (the right side's road wheels may sit at other x): rest length
  // from the tensioner's preload; torsion preloads that hold the arms at design under the static
  // load on flat ground (unless the file gives one); rigid-contact samples per ground-run segment.
  // (the chassis and the running gear's members; the belts and idlers are left out, as they
  // always were for this preload)
  vehicle_mass_kg_ = params.chassis.mass_kg;
  for (int s = 0; s < 2; ++s) vehicle_mass_kg_ += tp_.sprocket_mass_kg;
  for (int i = 0; i < 2 * n_rw_; ++i) vehicle_mass_kg_ += m_aw;
  const double wheel_load_n = vehicle_mass_kg_ * kGravity / (2.0 * n_rw_);
  const double spacing = tp_.contact_spacing_m;
  int offset = 0;
  for (int s = 0; s < 2; ++s) {
    BeltLoop loop;
    loop.n = n_rw_ + 2;
    loop.centre[0] = Vec2(tp_.sprocket_B.x(), tp_.sprocket_B.z());
    for (int k = 0; k < n_rw_; ++k) loop.centre[k + 1] = Vec2(RoadWheelX(s, k), tp_.road_wheel_z_m);
    loop.centre[n_rw_ + 1] = Vec2(tp_.idler_B.x(), tp_.idler_B.z());
    Vec2 grad[kMaxBeltWheels];
    const double length = BeltLength(loop, grad);
    const Vec2 idler_dir = Vec2(tp_.idler_B.x() < tp_.sprocket_B.x() ? -1.0 : 1.0, 0.0);
    const double dl_ds = grad[n_rw_ + 1].dot(idler_dir);
    VB_DEMAND(dl_ds > 1e-3);
    const double tension = tp_.tensioner_preload_n / dl_ds;
    belt_rest_length_m_[s] = length - tension / tp_.belt_stiffness_npm;
    state_.tension_n[s] = tension;
    for (int k = 0; k < n_rw_; ++k) {
      if (tp_.torsion_preload_nm != 0.0) {
        preload_nm_[s][k] = tp_.torsion_preload_nm;
        continue;
      }
      // torque balance at angle 0: preload + belt pull + ground load + the arm's own weight = 0
      const Vec2 rate = RotationRate(wheel_from_pivot);
      const double belt = -tension * grad[k + 1].dot(rate);
      const double ground = wheel_load_n * rate.y();
      const double weight = -m_aw * kGravity * RotationRate(com_from_pivot).y();
      preload_nm_[s][k] = -(belt + ground + weight);
    }
    for (int k = 0; k + 1 < n_rw_ + 2; ++k) {
      const double len = (loop.centre[k + 1] - loop.centre[k]).norm();
      samples_per_segment_[s][k] = std::max(1, static_cast<int>(std::ceil(len / spacing)));
      sample_offset_[s][k] = offset;
      offset += samples_per_segment_[s][k];
    }
  }
  state_.bristle_W.assign(static_cast<size_t>(offset), Vec3::Zero());
  sprocket_speeds_.assign(2, 0.0);
  sprocket_torques_.assign(2, 0.0);
  driven_.assign(2, true);
}

void TrackRunningGear::Attach(engine::PhysicsWorld* world, engine::MultiBodyId body) {
  world_ = world;
  body_ = body;
}

double TrackRunningGear::SprocketSpeed(int side) const {
  return world_->JointVelocity(body_, sides_[side].sprocket_link);
}

double TrackRunningGear::RoadWheelX(int side, int k) const { return RoadWheelXOf(tp_, side, k); }

Vec3 TrackRunningGear::ArmPivot_B(int s, int k) const {
  return ArmPivotOf(tp_, s, k);
}

Vec3 TrackRunningGear::RoadWheelCentre_B(int s, int k, double q) const {
  return ArmPivot_B(s, k) + TurnAboutY(wheel_from_pivot_L_, q);
}

Vec3 TrackRunningGear::IdlerCentre_B(int s) const {
  const double dir = tp_.idler_B.x() < tp_.sprocket_B.x() ? -1.0 : 1.0;
  return Vec3(tp_.idler_B.x() + dir * state_.idler_travel_m[s], sides_[s].sign * tp_.half_gauge_m,
              tp_.idler_B.z());
}

void TrackRunningGear::Synchronize(const DriverInputs& inputs, const terrain::Terrain& terrain,
                                   soil::SoilContact* soil,
                                   const terrain::ObstacleField* obstacles,
                                   terrain::ContactScratch* scratch, double dt,
                                   std::vector<WheelState>* wheels) {
  // Powertrain: engine through the gearbox and an open differential to the two sprockets.
  for (int s = 0; s < 2; ++s) sprocket_speeds_[s] = SprocketSpeed(s);
  const Pose com = world_->BasePose(body_);
  const double ground_speed =
      world_->BaseLinearVelocity(body_).dot(com.rotation * Vec3::UnitX());
  ComputeWheelTorques(params_, inputs.throttle, sprocket_speeds_, driven_, ground_speed, dt,
                      &state_.powertrain, &sprocket_torques_);
  // The chassis's acceleration for the arms: the last step's (their inertia in the chassis frame
  // lags it by one step; the arms are ~1 % of the vehicle's mass each).
  const Vec3 v = world_->BaseLinearVelocity(body_), w = world_->BaseAngularVelocity(body_);
  accel_com_W_.setZero();
  alpha_W_.setZero();
  if (state_.has_last_base_velocity) {
    accel_com_W_ = (v - state_.last_base_velocity_W) / dt;
    alpha_W_ = (w - state_.last_base_omega_W) / dt;
  }
  state_.last_base_velocity_W = v;
  state_.last_base_omega_W = w;
  state_.has_last_base_velocity = true;
  gravity_W_ = world_->Gravity();
  wheel_obstacles_.clear();
  for (int s = 0; s < 2; ++s) SynchronizeSide(s, inputs, terrain, soil, obstacles, scratch, dt, wheels);
}

void TrackRunningGear::AdvanceArm(int s, int k, double torque, double dt) {
  const Pose com = world_->BasePose(body_);
  const Mat3 R = com.rotation.toRotationMatrix();
  const Vec3 w_com = world_->BaseAngularVelocity(body_);
  const Vec3 axis_W = R.col(1);
  const double q = state_.arm_q[s][k], qd = state_.arm_qd[s][k];
  const Vec3 pivot_W = com.position + R * (ArmPivot_B(s, k) - com_B_);
  const Vec3 c_W = R * TurnAboutY(com_from_pivot_L_, q);   // pivot to the member's COM
  // The pivot's acceleration; the member's weight and inertia in the chassis frame.
  const Vec3 r = pivot_W - com.position;
  const Vec3 a_pivot = accel_com_W_ + alpha_W_.cross(r) + w_com.cross(w_com.cross(r));
  const double m = arm_mass_kg_, inertia = arm_pivot_inertia_kgm2_;
  const double load = torque + axis_W.dot(c_W.cross(m * (gravity_W_ - a_pivot))) -
                      inertia * alpha_W_.dot(axis_W);
  double qd_new = qd + load / inertia * dt;
  // Obstacle contacts: the wheel's contact point must not approach the obstacle faster than the
  // error reduction allows, v_n = v_chassis(p).n + g qd >= beta depth / dt with g the point's
  // normal speed per unit rate (one degree of freedom: the most demanding contact binds).
  const int first = obstacle_begin_[s][k], end = obstacle_begin_[s][k + 1];
  const double qd_free = qd_new;
  int binding = -1;
  double g_binding = 0.0;
  if (first < end) {
    const Vec3 v_com = world_->BaseLinearVelocity(body_);
    for (int i = first; i < end; ++i) {
      WheelObstacle& o = wheel_obstacles_[static_cast<size_t>(i)];
      const terrain::BodyContact& c = o.contact;
      const double g = axis_W.cross(c.point_W - pivot_W).dot(c.normal_W);
      o.on_arm = g >= kMinArmYield_mprad;
      if (!o.on_arm) continue;
      const double v_chassis = (v_com + w_com.cross(c.point_W - com.position)).dot(c.normal_W);
      const double qd_needed = (kObstacleErrorReduction * c.depth_m / dt - v_chassis) / g;
      if (qd_needed > qd_new) {
        qd_new = qd_needed;
        binding = i;
        g_binding = g;
      }
    }
  }
  double q_new = q + qd_new * dt;
  // The hard travel limits beyond the stops: inelastic.
  const double lo = -tp_.rebound_angle_rad - kArmHardLimitBeyondStops_rad;
  const double hi = tp_.bump_angle_rad + kArmHardLimitBeyondStops_rad;
  if (q_new > hi || q_new < lo) {
    q_new = std::clamp(q_new, lo, hi);
    qd_new = 0.0;
    // an arm at its hard limit cannot yield: its obstacle contacts are the solver's
    if (first < end && q_new == hi) {
      for (int i = first; i < end; ++i) wheel_obstacles_[static_cast<size_t>(i)].on_arm = false;
      binding = -1;
    }
  }
  obstacle_torque_nm_[s][k] = 0.0;
  if (binding >= 0) {
    // the obstacle's force on the member (along the binding contact's normal, at its point),
    // which the chassis receives as it receives the ground force: the member passes it on, less
    // what accelerates it (below)
    const double impulse = inertia * (qd_new - qd_free);   // N m s about the pivot
    const terrain::BodyContact& c = wheel_obstacles_[static_cast<size_t>(binding)].contact;
    world_->ApplyBaseForce(body_, (impulse / (g_binding * dt)) * c.normal_W, c.point_W);
    obstacle_torque_nm_[s][k] = impulse / dt;
  }
  state_.arm_q[s][k] = q_new;
  state_.arm_qd[s][k] = qd_new;
  // The chassis carries the member's mass at design: it gets the member's external forces (the
  // caller applied them) less what accelerates the member relative to it (tangential,
  // centripetal and Coriolis terms at the COM, and its own spin about the axis).
  const double qdd = (qd_new - qd) / dt;
  const Vec3 t_W = axis_W.cross(c_W);   // COM velocity per unit rate
  const Vec3 a_rel = qdd * t_W - qd * qd * c_W + 2.0 * qd * w_com.cross(t_W);
  world_->ApplyBaseForce(body_, -m * a_rel, pivot_W + c_W);
  world_->ApplyBaseTorque(body_, -tp_.arm_inertia_kgm2.y() * qdd * axis_W);
}

void TrackRunningGear::SynchronizeSide(int s, const DriverInputs& inputs,
                                       const terrain::Terrain& terrain, soil::SoilContact* soil,
                                       const terrain::ObstacleField* obstacles,
                                       terrain::ContactScratch* scratch, double dt,
                                       std::vector<WheelState>* wheels) {
  const Side& side = sides_[s];
  const Pose com = world_->BasePose(body_);
  const Mat3 R = com.rotation.toRotationMatrix();
  const Vec3 ref_W = com.position - R * com_B_;
  const Vec3 up_W = R.col(2);
  const Vec3 lat_W = R.col(1);
  const Vec3 v_com = world_->BaseLinearVelocity(body_);
  const Vec3 w_com = world_->BaseAngularVelocity(body_);
  const double y = side.sign * tp_.half_gauge_m;
  const int n_pts = n_rw_ + 2;
  const int idler = n_rw_ + 1;

  // Wheel centres (world and chassis frame).
  Vec3 centre_W[kMaxBeltWheels];
  BeltLoop loop;
  loop.n = n_pts;
  const Vec3 sprocket_B(tp_.sprocket_B.x(), y, tp_.sprocket_B.z());
  centre_W[0] = ref_W + R * sprocket_B;
  loop.centre[0] = Vec2(sprocket_B.x(), sprocket_B.z());
  Vec3 pivot_W[kMaxRoadWheels];
  for (int k = 0; k < n_rw_; ++k) {
    const Vec3 pivot_B = ArmPivot_B(s, k);
    const Vec3 c_B = pivot_B + TurnAboutY(wheel_from_pivot_L_, state_.arm_q[s][k]);
    pivot_W[k] = ref_W + R * pivot_B;
    centre_W[k + 1] = ref_W + R * c_B;
    loop.centre[k + 1] = Vec2(c_B.x(), c_B.z());
  }
  // The road wheels' obstacle contacts at the step's start (the arms take them in AdvanceArm).
  const double rw_radius = tp_.road_wheel_radius_m + tp_.shoe_height_m;
  for (int k = 0; k < n_rw_; ++k) {
    obstacle_begin_[s][k] = static_cast<int>(wheel_obstacles_.size());
    if (obstacles == nullptr) continue;
    obstacle_query_.clear();
    terrain::WheelObstacleContacts(centre_W[k + 1], lat_W, rw_radius, 0.5 * tp_.shoe_width_m,
                                   *obstacles, tp_.friction, kMaxObstacleContactsPerWheel, scratch,
                                   &obstacle_query_);
    for (const terrain::BodyContact& c : obstacle_query_) wheel_obstacles_.push_back({c, false});
  }
  obstacle_begin_[s][n_rw_] = static_cast<int>(wheel_obstacles_.size());
  const Vec3 idler_B = IdlerCentre_B(s);
  centre_W[idler] = ref_W + R * idler_B;
  loop.centre[idler] = Vec2(idler_B.x(), idler_B.z());

  // Tensioner and belt: the idler carrier is light and stiffly held, so it is solved
  // quasi-statically (backward Euler on the massless carrier with its damper): tensioner force
  // = belt pull on the idler, f0 - k s - c (s - s_old) / dt = T dL/ds, T = k_b (L(s) - L0) >= 0,
  // L linear in s about the current travel.
  Vec2 grad[kMaxBeltWheels];
  const Vec2 idler_dir(tp_.idler_B.x() < tp_.sprocket_B.x() ? -1.0 : 1.0, 0.0);
  {
    const double s_old = state_.idler_travel_m[s];
    const double l_old = BeltLength(loop, grad);
    const double g = grad[idler].dot(idler_dir);
    const double kt = tp_.tensioner_stiffness_npm, kb = tp_.belt_stiffness_npm;
    const double cdt = tp_.tensioner_damping_nspm / dt;
    const double slack0 = l_old - g * s_old - belt_rest_length_m_[s];  // belt stretch at s = 0
    double s_new = (tp_.tensioner_preload_n + cdt * s_old - kb * g * slack0) / (kt + cdt + kb * g * g);
    if (slack0 + g * s_new < 0.0) s_new = (tp_.tensioner_preload_n + cdt * s_old) / (kt + cdt);
    s_new = std::clamp(s_new, -kIdlerTravel_m, kIdlerTravel_m);
    state_.idler_travel_m[s] = s_new;
    centre_W[idler] = ref_W + R * IdlerCentre_B(s);
    loop.centre[idler] += (s_new - s_old) * idler_dir;
  }
  const double length = BeltLength(loop, grad);
  const double tension = tp_.belt_stiffness_npm * std::max(0.0, length - belt_rest_length_m_[s]);
  state_.tension_n[s] = tension;
  const Vec2 pivot_offset(tp_.arm_pivot_offset_B.x(), tp_.arm_pivot_offset_B.z());
  // Arm torques: torsion bar (damping implicit on the arm's inertia about the pivot), stops and
  // the belt's pull; the ground's is added below.
  double arm_torque[kMaxRoadWheels];
  for (int k = 0; k < n_rw_; ++k) {
    const Vec2 pivot = Vec2(RoadWheelX(s, k), tp_.road_wheel_z_m) + pivot_offset;
    const Vec2 d = loop.centre[k + 1] - pivot;
    const double belt = -tension * grad[k + 1].dot(Vec2(d.y(), -d.x()));
    const double q = state_.arm_q[s][k];
    const double qd = state_.arm_qd[s][k];
    double torque = preload_nm_[s][k] - tp_.torsion_stiffness_nmprad * q -
                    ImplicitDamping(tp_.torsion_damping_nmsprad, dt, arm_damping_inertia_kgm2_) *
                        qd +
                    belt;
    if (q > tp_.bump_angle_rad) torque -= tp_.stop_stiffness_nmprad * (q - tp_.bump_angle_rad);
    if (q < -tp_.rebound_angle_rad) {
      torque += tp_.stop_stiffness_nmprad * (-tp_.rebound_angle_rad - q);
    }
    arm_torque[k] = torque;
  }
  // Ground run: bottom points and their structure velocities.
  const double h = tp_.shoe_height_m;
  run_[0].p_W = centre_W[0] - (tp_.sprocket_radius_m + h) * up_W;
  run_[0].v_W = v_com + w_com.cross(run_[0].p_W - com.position);
  const Vec3 axis_W = R.col(1);
  for (int k = 0; k < n_rw_; ++k) {
    RunPoint& rp = run_[k + 1];
    rp.p_W = centre_W[k + 1] - (tp_.road_wheel_radius_m + h) * up_W;
    rp.v_W = v_com + w_com.cross(rp.p_W - com.position) +
             state_.arm_qd[s][k] * axis_W.cross(rp.p_W - pivot_W[k]);
  }
  run_[idler].p_W = centre_W[idler] - (tp_.idler_radius_m + h) * up_W;
  run_[idler].v_W = v_com + w_com.cross(run_[idler].p_W - com.position);
  Vec3 seg_fwd[kMaxBeltWheels];
  for (int k = 0; k + 1 < n_pts; ++k) {
    const Vec3 d = run_[k].p_W - run_[k + 1].p_W;
    const double n = d.norm();
    seg_fwd[k] = n > 1e-9 ? Vec3(d / n) : Vec3(R.col(0));
  }
  for (int i = 0; i < n_pts; ++i) {
    Vec3 t = i == 0 ? seg_fwd[0] : i == n_pts - 1 ? seg_fwd[n_pts - 2]
                                                  : Vec3(seg_fwd[i - 1] + seg_fwd[i]);
    run_[i].tangent_W = t.normalized();
    run_[i].force_W.setZero();
    run_[i].along_W.setZero();
  }
  const double omega = world_->JointVelocity(body_, side.sprocket_link);
  const double belt_speed = omega * tp_.sprocket_radius_m;  // the ground run moves back at this

  // Soil first: it claims the segments over deformable ground.
  bool on_soil[kMaxBeltWheels] = {};
  double sinkage[kMaxBeltWheels] = {};
  terrain::SurfaceClass seg_surface[kMaxBeltWheels] = {};
  // The contact acts on the light arms first: the stiff and damping terms are made implicit
  // (and the soil's stiffness capped) on the unsprung mass along the run, not on the chassis.
  const double side_mass = n_rw_ * (tp_.arm_mass_kg + tp_.road_wheel_mass_kg);
  double belt_force = 0.0;   // ground force along the belt, carried to the sprocket
  if (soil != nullptr) {
    soil::TrackSoilInput in;
    in.track_id = s;
    in.n_points = n_pts;
    for (int i = 0; i < n_pts; ++i) {
      in.points_W[i] = run_[i].p_W;
      in.velocities_W[i] = run_[i].v_W - belt_speed * run_[i].tangent_W;
    }
    in.lateral_W = lat_W;
    in.width_m = tp_.shoe_width_m;
    in.mass_kg = side_mass;
    const soil::TrackSoilOutput out = soil->TrackContact(in, dt);
    for (int i = 0; i < n_pts; ++i) {
      // the soil's pressure acts along the belt's normal, its shear in the belt's plane: the
      // shear's component along the belt is what the belt carries
      const Vec3& f = out.point_force_W[i];
      const double along = f.dot(run_[i].tangent_W);
      belt_force += along;
      run_[i].along_W += along * run_[i].tangent_W;
      run_[i].force_W += f - along * run_[i].tangent_W;
      sinkage[i] = out.point_sinkage_m[i];
    }
    for (int k = 0; k + 1 < n_pts; ++k) {
      on_soil[k] = out.segment_on_soil[k];
      seg_surface[k] = out.segment_surface[k];
    }
  }

  // Rigid ground: samples along the other segments.
  double total_len = 0.0;
  for (int k = 0; k + 1 < n_pts; ++k) total_len += (run_[k].p_W - run_[k + 1].p_W).norm();
  for (int k = 0; k + 1 < n_pts; ++k) {
    const int n_s = samples_per_segment_[s][k];
    Vec3* bristles = &state_.bristle_W[static_cast<size_t>(sample_offset_[s][k])];
    if (on_soil[k]) {
      for (int m = 0; m < n_s; ++m) bristles[m].setZero();
      continue;
    }
    const Vec3& a = run_[k].p_W;
    const Vec3& b = run_[k + 1].p_W;
    const double len = (b - a).norm();
    const double ell = len / n_s;
    const double sample_mass = side_mass * ell / std::max(total_len, 1e-6);
    const Vec3 va = run_[k].v_W - belt_speed * run_[k].tangent_W;
    const Vec3 vb = run_[k + 1].v_W - belt_speed * run_[k + 1].tangent_W;
    for (int m = 0; m < n_s; ++m) {
      const double t = (m + 0.5) / n_s;
      const Vec3 p = (1.0 - t) * a + t * b;
      const terrain::SurfacePoint g = terrain.Query(p.x(), p.y());
      if (m == n_s / 2) seg_surface[k] = g.surface;
      const double depth = (g.height_m - p.z()) * g.normal_W.z();
      if (!(depth > 0.0)) {
        bristles[m].setZero();
        continue;
      }
      const Vec3& n = g.normal_W;
      const Vec3 v = (1.0 - t) * va + t * vb;
      const double vn = v.dot(n);
      const double c_n = ImplicitDamping(tp_.normal_damping_nspm2 * ell, dt, sample_mass);
      const double fn = std::max(0.0, tp_.normal_stiffness_npm2 * ell * depth - c_n * vn);
      const Vec3 vt = v - vn * n;
      Vec3& z = bristles[m];
      z += vt * dt;
      z -= z.dot(n) * n;
      const double k_b = tp_.bristle_stiffness_npm2 * ell;
      const double c_b = ImplicitDamping(tp_.bristle_damping_nspm2 * ell, dt, sample_mass);
      Vec3 ft = -k_b * z - c_b * vt;
      const double mu = std::min(tp_.friction, g.friction);
      const double limit = mu * fn;
      const double ft_norm = ft.norm();
      if (ft_norm > limit) {
        ft *= limit / ft_norm;
        z = -ft / k_b;   // the bristle slides at the Coulomb limit
      }
      // friction along the belt is carried by the belt to the sprocket; the pressure (along the
      // ground normal) and the side friction go to the structure under the point
      const double along = ft.dot(seg_fwd[k]);
      belt_force += along;
      const Vec3 along_W = along * seg_fwd[k];
      const Vec3 rest = fn * n + ft - along_W;
      run_[k].force_W += (1.0 - t) * rest;
      run_[k + 1].force_W += t * rest;
      run_[k].along_W += (1.0 - t) * along_W;
      run_[k + 1].along_W += t * along_W;
    }
  }

  // Apply: along the belt to the chassis and against the sprocket, the rest to the body under
  // the point (an arm passes it to the chassis, which carries the arm's mass, and turns under its
  // moment about the pivot).
  for (int i = 0; i < n_pts; ++i) {
    const RunPoint& rp = run_[i];
    const Vec3& rest = rp.force_W;
    world_->ApplyBaseForce(body_, rp.along_W + rest, rp.p_W);
    if (i != 0 && i != idler) {
      arm_torque[i - 1] += axis_W.dot((rp.p_W - pivot_W[i - 1]).cross(rest));
    }
  }
  for (int k = 0; k < n_rw_; ++k) AdvanceArm(s, k, arm_torque[k], dt);
  thrust_n_[s] = belt_force;
  world_->AddJointForce(body_, side.sprocket_link,
                        sprocket_torques_[s] - belt_force * tp_.sprocket_radius_m);
  // Brakes (service and steering): an implicit velocity motor on the sprocket.
  const double steer_brake = s == 0 ? std::max(0.0, inputs.steering) : std::max(0.0, -inputs.steering);
  const double braking = std::min(1.0, inputs.braking + steer_brake);
  world_->SetJointVelocityMotor(body_, side.sprocket_link, 0.0, braking * tp_.brake_torque_nm);

  // Road-wheel records.
  for (int k = 0; k < n_rw_; ++k) {
    WheelState& ws = (*wheels)[static_cast<size_t>(2 * k + s)];
    const Vec3& f = run_[k + 1].force_W;
    ws.normal_force_n = std::max(0.0, f.dot(up_W));
    ws.in_contact = ws.normal_force_n > 0.0;
    const bool soil_here = on_soil[k] || on_soil[k + 1];
    ws.surface = on_soil[k + 1] ? seg_surface[k + 1] : seg_surface[k];
    ws.sinkage_m = soil_here ? sinkage[k + 1] : 0.0;
  }
}

void TrackRunningGear::UpdateWheelStates(std::vector<WheelState>* wheels) const {
  const Pose com = world_->BasePose(body_);
  const Vec3 fwd = com.rotation * Vec3::UnitX();
  const Vec3 axis_W = com.rotation * Vec3::UnitY();
  const Vec3 v_com = world_->BaseLinearVelocity(body_);
  const Vec3 w_com = world_->BaseAngularVelocity(body_);
  for (int s = 0; s < 2; ++s) {
    const double u = SprocketSpeed(s) * tp_.sprocket_radius_m;
    for (int k = 0; k < n_rw_; ++k) {
      WheelState& ws = (*wheels)[static_cast<size_t>(2 * k + s)];
      const double q = state_.arm_q[s][k];
      const Vec3 pivot_W = com.position + com.rotation * (ArmPivot_B(s, k) - com_B_);
      ws.center_W = com.position + com.rotation * (RoadWheelCentre_B(s, k, q) - com_B_);
      ws.spin_radps = u / tp_.road_wheel_radius_m;
      ws.suspension_travel_m = q * std::abs(tp_.arm_pivot_offset_B.x());
      const double v = (v_com + w_com.cross(ws.center_W - com.position) +
                        state_.arm_qd[s][k] * axis_W.cross(ws.center_W - pivot_W))
                           .dot(fwd);
      ws.longitudinal_slip = (u - v) / std::max({std::abs(u), std::abs(v), 0.1});
    }
  }
}

void TrackRunningGear::AddObstacleContacts() {
  for (const WheelObstacle& o : wheel_obstacles_) {
    const terrain::BodyContact& c = o.contact;
    if (o.on_arm) {
      if (c.obstacle_tag >= 0) world_->ReportObstacleTouch(body_, c.obstacle_tag);
      continue;
    }
    world_->AddContact({body_, -1, c.point_W, c.normal_W, c.depth_m, c.friction, c.obstacle_tag});
  }
}

}  // namespace vb::vehicles
