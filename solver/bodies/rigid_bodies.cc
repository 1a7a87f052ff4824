#include "solver/bodies/rigid_bodies.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "solver/physics/body_force.h"

namespace sph {

template <int D>
RigidBodies<D>::RigidBodies(ParticleStore<D>& s, const v1::Case& c,
                            const std::vector<double>& solid_density,
                            const std::vector<double>& fluid_density_of_body)
    : s_(s),
      body_(s.template add<std::int32_t>("body", kName, true)),
      offset_(s.template add<Vec<D>>("body_offset", kName, true)),
      accel_(s.template add<Vec<D>>("wall_acceleration", kName, true)),
      fluid_force_(s.template add<Vec<D>>("rigid_fluid_force", kName, false)),
      spin_lever_(s.template add<Vec<D>>("rigid_spin_lever", kName, false)) {
  spin_lever_.set_ghost(false);
  // Persistent: set when the bodies move, before particles migrate, and read by the wall
  // condition after; ghosts do not need it.
  accel_.set_ghost(false);
  for (int k = 0; k < c.bodies_size(); ++k) {
    const auto& pb = c.bodies(k);
    RigidBody<D> b;
    b.source = k;
    b.serial = k;
    b.name = pb.name().empty() ? "body_" + std::to_string(k) : pb.name();
    switch (pb.motion_type()) {
      case v1::FIXED:
        b.motion = BodyMotion::kFixed;
        break;
      case v1::PRESCRIBED:
        b.motion = BodyMotion::kPrescribed;
        break;
      case v1::PINNED:
        b.motion = BodyMotion::kPinned;
        break;
      case v1::PRESCRIBED_ROTATION:
        b.motion = BodyMotion::kPrescribedRotation;
        break;
      default:
        b.motion = BodyMotion::kFree;
    }
    if (b.motion == BodyMotion::kPrescribed || b.motion == BodyMotion::kPrescribedRotation)
      b.path = MotionPath(pb.motion(), D);
    const double rho_s = solid_density[static_cast<size_t>(k)];
    // Buoyancy-reduced body force b = (rho_s - rho_f)/rho_s g (Fuchs 2021, falling disk).
    if (pb.body_force() == v1::BUOYANCY_REDUCED)
      b.body_force_factor = (rho_s - fluid_density_of_body[static_cast<size_t>(k)]) / rho_s;
    bodies_.push_back(b);
  }
  case_bodies_ = bodies_.size();
  bodies_made_ = static_cast<std::int64_t>(bodies_.size());
}

template <int D>
Vec<D> RigidBodies<D>::body_force(const RigidBody<D>& b, double t) const {
  return b.body_force_factor * BodyForce<D>::damping_factor(t, t_damp_) * g_;
}

template <int D>
void RigidBodies<D>::initialize(const Comm& comm, double dx, const std::vector<Vec<D>>& v0,
                                const std::vector<AngVec<D>>& w0) {
  const std::size_t nb = bodies_.size();
  // Pass 1 (eqs. 20, 22): mass and first moment.
  const std::size_t s1 = 2 + D;  // mass, count, m x
  auto first = exact_sum(
      nb * s1,
      [&](auto emit) {
        for (std::size_t i = 0; i < s_.owned(); ++i) {
          if (s_.kind[i] != Kind::kRigid) continue;
          const std::size_t k = static_cast<std::size_t>(body_[i]) * s1;
          emit(k, s_.m[i]);
          emit(k + 1, 1.0);
          for (int a = 0; a < D; ++a) emit(k + 2 + static_cast<size_t>(a), s_.m[i] * s_.x[i][a]);
        }
      },
      comm);
  for (std::size_t k = 0; k < nb; ++k) {
    RigidBody<D>& b = bodies_[k];
    b.mass = first[k * s1];
    b.particles = static_cast<std::int64_t>(std::llround(first[k * s1 + 1]));
    for (int a = 0; a < D; ++a) b.com[a] = first[k * s1 + 2 + static_cast<size_t>(a)] / b.mass;
    b.com0 = b.com;
  }
  // Pass 2 (eqs. 21, 23): inertia about the centre of mass, with the particles' own inertia
  // (Remark 13): disks of radius dx/sqrt(pi) in 2D, spheres of radius (3/(4 pi))^(1/3) dx in 3D.
  const double self = self_inertia_per_mass(dx);
  const std::size_t s2 = A * A;
  auto second = exact_sum(
      nb * s2,
      [&](auto emit) {
        for (std::size_t i = 0; i < s_.owned(); ++i) {
          if (s_.kind[i] != Kind::kRigid) continue;
          const std::size_t k = static_cast<std::size_t>(body_[i]);
          const Vec<D> r = s_.x[i] - bodies_[k].com;
          const double m = s_.m[i];
          if constexpr (D == 2) {
            emit(k, m * (r.squaredNorm() + self));
          } else {
            for (int p = 0; p < 3; ++p)
              for (int q = 0; q < 3; ++q)
                emit(k * s2 + static_cast<size_t>(3 * p + q),
                     m * ((p == q ? r.squaredNorm() + self : 0.0) - r[p] * r[q]));
          }
        }
      },
      comm);
  for (std::size_t k = 0; k < nb; ++k) {
    RigidBody<D>& b = bodies_[k];
    for (int p = 0; p < A; ++p)
      for (int q = 0; q < A; ++q)
        b.inertia_body(p, q) = second[k * s2 + static_cast<size_t>(A * p + q)];
    b.velocity = b.translates_freely() ? v0[k] : Vec<D>::Zero();
    b.omega = b.rotates_freely() ? w0[k] : AngVec<D>::Zero();
    if (b.motion == BodyMotion::kPrescribedRotation) set_prescribed_rotation(b, 0.0);
    b.angular_momentum = b.world_inertia_times(b.omega);
  }
  for (std::size_t i = 0; i < s_.owned(); ++i)
    if (s_.kind[i] == Kind::kRigid)
      offset_[i] = s_.x[i] - bodies_[static_cast<size_t>(body_[i])].com;
  update_accelerations(0.0);
}

template <int D>
double RigidBodies<D>::self_inertia_per_mass(double dx) {
  const double r_eff =
      D == 2 ? dx / std::sqrt(std::numbers::pi) : std::cbrt(0.75 / std::numbers::pi) * dx;
  return (D == 2 ? 0.5 : 0.4) * r_eff * r_eff;
}

template <int D>
void RigidBodies<D>::kick(double h, double t) {
  for (RigidBody<D>& b : bodies_) {
    if (b.translates_freely()) b.velocity += h * (b.fluid_force / b.mass + body_force(b, t));
    if (!b.rotates_freely()) continue;
    // L' = L + h (T_rest + C omega'), omega' = I_w^-1 L': (1 - h C I_w^-1) L' = L + h T_rest.
    // C damps (its discrete sum is negative definite for a body the fluid surrounds); without
    // it, or should it not damp, the kick is explicit in the whole torque.
    if constexpr (D == 2) {
      const double denominator = 1.0 - h * b.spin_damping(0, 0) / b.inertia_body(0, 0);
      if (denominator > 1.0)
        b.omega = (b.omega + h * b.inverse_inertia(b.fluid_torque_rest)) / denominator;
      else
        b.omega += h * b.inverse_inertia(b.fluid_torque);
    } else {
      Eigen::Matrix3d inv;
      for (int a = 0; a < 3; ++a) inv.col(a) = b.inverse_inertia(Eigen::Vector3d::Unit(a));
      const Eigen::Matrix3d m = Eigen::Matrix3d::Identity() - h * b.spin_damping * inv;
      if (!b.spin_damping.isZero() && m.determinant() >= 1.0)
        b.angular_momentum = m.partialPivLu().solve(b.angular_momentum + h * b.fluid_torque_rest);
      else
        b.angular_momentum += h * b.fluid_torque;
      b.update_omega();
    }
  }
}

template <int D>
void RigidBodies<D>::set_prescribed_rotation(RigidBody<D>& b, double t) {
  const double w = b.path.angular_velocity(t), angle = b.path.angle(t);
  if constexpr (D == 2) {
    b.orientation.angle = angle;
    b.omega[0] = w;
  } else {
    b.orientation.q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, b.path.axis()));
    b.omega = w * b.path.axis();
  }
}

template <int D>
void RigidBodies<D>::drift(double dt, double t_end) {
  for (RigidBody<D>& b : bodies_) {
    if (!b.active()) continue;
    if (b.motion == BodyMotion::kPrescribedRotation) {
      b.com += dt * b.velocity;  // eq. 33
      set_prescribed_rotation(b, t_end);
      b.angular_momentum = b.world_inertia_times(b.omega);
    } else if (b.motion == BodyMotion::kFree || b.motion == BodyMotion::kPinned) {
      if (b.motion == BodyMotion::kFree) b.com += dt * b.velocity;  // eq. 33
      if constexpr (D == 3) {
        // Eqs. 34-35 with the angular velocity of the mid-step orientation: with L fixed
        // during the drift, omega = I_w(q)^-1 L turns with the body, and evaluating it at
        // the predicted midpoint makes the update second order (energy error O(dt^2)).
        RigidBody<D> mid = b;
        mid.orientation.rotate(b.omega, 0.5 * dt);
        mid.update_omega();
        b.omega = mid.omega;
      }
      b.orientation.rotate(b.omega, dt);
    } else if (b.motion == BodyMotion::kPrescribed) {
      Point3 c0 = Point3::Zero();
      for (int a = 0; a < D; ++a) c0[a] = b.com0[a];
      const Point3 c = b.path.position(c0, t_end), v = b.path.velocity(c0, t_end);
      for (int a = 0; a < D; ++a) {
        b.com[a] = c[a];
        b.velocity[a] = v[a];
      }
      set_prescribed_rotation(b, t_end);
    }
  }
}

template <int D>
void RigidBodies<D>::place_owned_particles() {
  std::vector<RotationMatrix<D>> R(bodies_.size());
  for (std::size_t k = 0; k < bodies_.size(); ++k) R[k] = bodies_[k].orientation.matrix();
  for (std::size_t i = 0; i < s_.owned(); ++i) {
    if (s_.kind[i] != Kind::kRigid) continue;
    const std::size_t k = static_cast<std::size_t>(body_[i]);
    const RigidBody<D>& b = bodies_[k];
    const Vec<D> r = R[k] * offset_[i];
    s_.x[i] = b.com + r;                          // eq. 36
    s_.v[i] = b.velocity + cross<D>(b.omega, r);  // eq. 36
    accel_[i] = b.acceleration + cross<D>(b.angular_acceleration, r) +
                cross<D>(b.omega, cross<D>(b.omega, r));
  }
}

template <int D>
void RigidBodies<D>::update_owned_velocities() {
  std::vector<RotationMatrix<D>> R(bodies_.size());
  for (std::size_t k = 0; k < bodies_.size(); ++k) R[k] = bodies_[k].orientation.matrix();
  for (std::size_t i = 0; i < s_.owned(); ++i) {
    if (s_.kind[i] != Kind::kRigid) continue;
    const std::size_t k = static_cast<std::size_t>(body_[i]);
    s_.v[i] = bodies_[k].velocity + cross<D>(bodies_[k].omega, R[k] * offset_[i]);  // eq. 40
  }
}

template <int D>
void RigidBodies<D>::reduce_fluid_forces(const Comm& comm) {
  const std::size_t per = D + A + A * A;
  std::vector<RotationMatrix<D>> R(bodies_.size());
  for (std::size_t k = 0; k < bodies_.size(); ++k) R[k] = bodies_[k].orientation.matrix();
  const auto sums = exact_sum(
      bodies_.size() * per,
      [&](auto emit) {
        for (std::size_t i = 0; i < s_.owned(); ++i) {
          if (s_.kind[i] != Kind::kRigid) continue;
          const std::size_t k = static_cast<std::size_t>(body_[i]);
          const Vec<D>& f = fluid_force_[i];
          const Vec<D> r = R[k] * offset_[i];
          const AngVec<D> m = moment<D>(r, f);  // eq. 25 with r_rk = R b_r
          for (int a = 0; a < D; ++a) emit(k * per + static_cast<size_t>(a), f[a]);
          for (int a = 0; a < A; ++a) emit(k * per + D + static_cast<size_t>(a), m[a]);
          // The torque r x (omega x g) of the lever g is C omega with C = (r . g) 1 - g r^T
          // (2D: r . g).
          const Vec<D>& g = spin_lever_[i];
          const std::size_t c0 = k * per + D + A;
          if constexpr (D == 2) {
            emit(c0, r.dot(g));
          } else {
            for (int a = 0; a < 3; ++a)
              for (int q = 0; q < 3; ++q)
                emit(c0 + static_cast<size_t>(3 * a + q), (a == q ? r.dot(g) : 0.0) - g[a] * r[q]);
          }
        }
      },
      comm);
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    RigidBody<D>& b = bodies_[k];
    for (int a = 0; a < D; ++a) b.fluid_force[a] = sums[k * per + static_cast<size_t>(a)];
    for (int a = 0; a < A; ++a) b.fluid_torque[a] = sums[k * per + D + static_cast<size_t>(a)];
    for (int a = 0; a < A * A; ++a)
      b.spin_damping(a / A, a % A) = sums[k * per + D + A + static_cast<size_t>(a)];
    // The pairs' torque plus the spin damping's (solver/physics/fluid_forces.h).
    b.fluid_torque_rest = b.fluid_torque;
    b.fluid_torque += b.spin_damping * b.omega;
  }
}

template <int D>
void RigidBodies<D>::update_accelerations(double t) {
  for (RigidBody<D>& b : bodies_) {
    if (!b.active()) continue;
    if (b.motion == BodyMotion::kFree || b.motion == BodyMotion::kPinned ||
        b.motion == BodyMotion::kPrescribedRotation) {
      // The contact reaches the fluid's wall condition only as far as it holds the body
      // against its other forces (see RigidBody::mean_contact_force).
      const Vec<D> smooth = b.fluid_force + b.mass * body_force(b, t);
      const double fc = b.mean_contact_force.norm();
      const double share = fc > smooth.norm() ? smooth.norm() / fc : 1.0;
      b.acceleration = b.translates_freely()
                           ? Vec<D>((smooth + share * b.mean_contact_force) / b.mass)
                           : Vec<D>(Vec<D>::Zero());
      if (b.rotates_freely()) {
        AngVec<D> m = b.fluid_torque + share * b.mean_contact_torque;
        if constexpr (D == 3)
          m -= AngVec<D>(Eigen::Vector3d(b.omega).cross(Eigen::Vector3d(b.angular_momentum)));
        b.angular_acceleration = b.inverse_inertia(m);
      } else if constexpr (D == 2) {
        b.angular_acceleration[0] = b.path.angular_acceleration(t);
      } else {
        b.angular_acceleration = b.path.angular_acceleration(t) * b.path.axis();
      }
    } else if (b.motion == BodyMotion::kPrescribed) {
      Point3 c0 = Point3::Zero();
      for (int a = 0; a < D; ++a) c0[a] = b.com0[a];
      const Point3 acc = b.path.acceleration(c0, t);
      for (int a = 0; a < D; ++a) b.acceleration[a] = acc[a];
      if constexpr (D == 2)
        b.angular_acceleration[0] = b.path.angular_acceleration(t);
      else
        b.angular_acceleration = b.path.angular_acceleration(t) * b.path.axis();
    } else {
      b.acceleration.setZero();
      b.angular_acceleration.setZero();
    }
  }
}

template <int D>
double RigidBodies<D>::total_mass() const {
  double m = 0;
  for (const auto& b : bodies_) m += b.mass;
  return m;
}

namespace {
template <class V>
void put(CheckpointState& st, const std::string& key, const V& v) {
  for (int a = 0; a < v.size(); ++a) st[key + "." + std::to_string(a)] = v[a];
}
template <class V>
void get(const CheckpointState& st, const std::string& key, V& v) {
  for (int a = 0; a < v.size(); ++a) v[a] = state_value(st, key + "." + std::to_string(a));
}
}  // namespace

template <int D>
void RigidBodies<D>::save(CheckpointState& st) const {
  // Phase transitions add bodies during a run: the count and what a new body was born as.
  st["bodies.case"] = static_cast<double>(case_bodies_);
  st["bodies.count"] = static_cast<double>(bodies_.size());
  st["bodies.made"] = static_cast<double>(bodies_made_);
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const RigidBody<D>& b = bodies_[k];
    const std::string p = "body." + std::to_string(k) + ".";
    st[p + "source"] = b.source;
    st[p + "serial"] = static_cast<double>(b.serial);
    st[p + "motion"] = static_cast<double>(b.motion);
    st[p + "force_factor"] = b.body_force_factor;
    st[p + "mass"] = b.mass;
    st[p + "particles"] = static_cast<double>(b.particles);
    put(st, p + "com0", b.com0);
    for (int a = 0; a < A * A; ++a)
      st[p + "inertia." + std::to_string(a)] = b.inertia_body(a / A, a % A);
    put(st, p + "com", b.com);
    put(st, p + "velocity", b.velocity);
    put(st, p + "omega", b.omega);
    put(st, p + "angular_momentum", b.angular_momentum);
    put(st, p + "fluid_force", b.fluid_force);
    put(st, p + "fluid_torque", b.fluid_torque);
    put(st, p + "fluid_torque_rest", b.fluid_torque_rest);
    for (int a = 0; a < A * A; ++a)
      st[p + "spin_damping." + std::to_string(a)] = b.spin_damping(a / A, a % A);
    put(st, p + "contact_force", b.contact_force);
    put(st, p + "contact_torque", b.contact_torque);
    put(st, p + "acceleration", b.acceleration);
    put(st, p + "angular_acceleration", b.angular_acceleration);
    // The dashpot's bound on the contact sub-step counts the touching pairs of the last
    // evaluation (SpringDashpotContact::dashpot_time_step): without them the first resumed
    // step could take a sub-step 2N times longer than the uninterrupted run.
    st[p + "contacts"] = static_cast<double>(b.contacts);
    if constexpr (D == 2)
      st[p + "angle"] = b.orientation.angle;
    else
      put(st, p + "quaternion", b.orientation.q.coeffs());
  }
}

template <int D>
void RigidBodies<D>::load(const CheckpointState& st) {
  // Body k of the checkpoint is body k of the case: another list of bodies would hand one
  // body's particles and momentum to another (checkpoints before "bodies.case" unchecked).
  if (const auto it = st.find("bodies.case");
      it != st.end() && static_cast<std::size_t>(it->second) != case_bodies_)
    throw std::runtime_error("the checkpoint was written for a case with " +
                             std::to_string(static_cast<long long>(it->second)) +
                             " rigid bodies in its list; this case has " +
                             std::to_string(case_bodies_));
  const auto count = st.find("bodies.count");
  if (count != st.end()) {
    const auto n = static_cast<std::size_t>(count->second);
    for (std::size_t k = bodies_.size(); k < n; ++k) {
      const std::string p = "body." + std::to_string(k) + ".";
      RigidBody<D> b;
      b.source = static_cast<int>(state_value(st, p + "source"));
      b.motion = static_cast<BodyMotion>(static_cast<int>(state_value(st, p + "motion")));
      b.body_force_factor = state_value(st, p + "force_factor");
      // A piece split off a body with prescribed motion follows that body's path.
      if (b.source >= 0) b.path = bodies_[static_cast<std::size_t>(b.source)].path;
      bodies_.push_back(b);
    }
  }
  // Checkpoints from before slots were reused have no serial numbers: slot = serial there.
  if (const auto it = st.find("bodies.made"); it != st.end())
    bodies_made_ = static_cast<std::int64_t>(it->second);
  else
    bodies_made_ = static_cast<std::int64_t>(bodies_.size());
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    RigidBody<D>& b = bodies_[k];
    const std::string p = "body." + std::to_string(k) + ".";
    if (const auto it = st.find(p + "serial"); it != st.end())
      b.serial = static_cast<std::int64_t>(it->second);
    else
      b.serial = static_cast<std::int64_t>(k);
    if (k >= case_bodies_) b.name = "body_" + std::to_string(b.serial);
    b.mass = state_value(st, p + "mass");
    b.particles = static_cast<std::int64_t>(state_value(st, p + "particles"));
    get(st, p + "com0", b.com0);
    for (int a = 0; a < A * A; ++a)
      b.inertia_body(a / A, a % A) = state_value(st, p + "inertia." + std::to_string(a));
    get(st, p + "com", b.com);
    get(st, p + "velocity", b.velocity);
    get(st, p + "omega", b.omega);
    get(st, p + "angular_momentum", b.angular_momentum);
    get(st, p + "fluid_force", b.fluid_force);
    get(st, p + "fluid_torque", b.fluid_torque);
    if (st.count(p + "spin_damping.0")) {
      get(st, p + "fluid_torque_rest", b.fluid_torque_rest);
      for (int a = 0; a < A * A; ++a)
        b.spin_damping(a / A, a % A) = state_value(st, p + "spin_damping." + std::to_string(a));
    } else {  // an older checkpoint: its torque had no spin damping
      b.fluid_torque_rest = b.fluid_torque;
      b.spin_damping.setZero();
    }
    get(st, p + "contact_force", b.contact_force);
    get(st, p + "contact_torque", b.contact_torque);
    get(st, p + "acceleration", b.acceleration);
    get(st, p + "angular_acceleration", b.angular_acceleration);
    if (const auto it = st.find(p + "contacts"); it != st.end())  // not in older checkpoints
      b.contacts = static_cast<std::int64_t>(it->second);
    if constexpr (D == 2)
      b.orientation.angle = state_value(st, p + "angle");
    else {
      auto c = b.orientation.q.coeffs();
      get(st, p + "quaternion", c);
      b.orientation.q.coeffs() = c;
    }
  }
}

template class RigidBodies<2>;
template class RigidBodies<3>;

}  // namespace sph
