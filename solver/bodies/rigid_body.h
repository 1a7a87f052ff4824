#pragma once
// The state of one rigid body made of particles (Fuchs 2021 "Modeling the motion of rigid
// bodies discretized by particles"): mass properties, orientation, velocities and the forces
// acting on it. The body table is replicated on every rank; partial sums over particles are
// reduced with exact_sum so every rank holds identical states (Fuchs eqs. 20-26 without an
// owning rank: the reduction gives all ranks the result the owner would broadcast).
//
// 2D: orientation is an angle, angular quantities are scalars about z.
// 3D: orientation is a unit quaternion (eqs. 34-35); the angular momentum L is integrated and
//     omega = I_w^-1 L with the world-frame inertia I_w = R I_b R^T, so torque-free motion
//     conserves L exactly (Euler's equations including the gyroscopic term, which eq. 7
//     leaves out for brevity; it vanishes for the paper's disks and spheres).
#include <Eigen/Geometry>
#include <string>

#include "case/motion.h"
#include "solver/core/types.h"

namespace sph {

template <int D>
using AngVec = Eigen::Matrix<double, D == 2 ? 1 : 3, 1>;  // angular quantities
template <int D>
using AngMat = Eigen::Matrix<double, D == 2 ? 1 : 3, D == 2 ? 1 : 3>;  // their linear maps

// kPinned: translation fixed at the centre of mass, rotation free (Reder et al. 2021 sec. 3.3);
// kPrescribedRotation: rotation about the centre of mass prescribed, translation free.
enum class BodyMotion { kFree, kFixed, kPrescribed, kPinned, kPrescribedRotation };

template <int D>
struct Orientation;

template <>
struct Orientation<2> {
  double angle = 0;
  Eigen::Matrix2d matrix() const { return Eigen::Rotation2Dd(angle).toRotationMatrix(); }
  // Eqs. 34-35 in 2D: the increment is an angle.
  void rotate(const AngVec<2>& omega, double dt) { angle += omega[0] * dt; }
};

template <>
struct Orientation<3> {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Matrix3d matrix() const { return q.toRotationMatrix(); }
  // Fuchs 2021 eqs. 34-35: increment phi = dt omega as a transition quaternion, q <- dq o q.
  void rotate(const AngVec<3>& omega, double dt) {
    const Eigen::Vector3d phi = dt * omega;
    const double angle = phi.norm();
    if (angle > 0) q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, phi / angle)) * q;
    q.normalize();
  }
};

// A body's rotation matrix (aligned Eigen storage, unlike the columns' Mat<D> of types.h).
template <int D>
using RotationMatrix = Eigen::Matrix<double, D, D>;

// omega x r (2D: omega about z).
template <int D>
inline Vec<D> cross(const AngVec<D>& w, const Vec<D>& r) {
  if constexpr (D == 2)
    return Vec<D>(-w[0] * r[1], w[0] * r[0]);
  else
    return Vec<D>(Eigen::Vector3d(w).cross(Eigen::Vector3d(r)));
}
// r x f (2D: the z component).
template <int D>
inline AngVec<D> moment(const Vec<D>& r, const Vec<D>& f) {
  if constexpr (D == 2)
    return AngVec<D>(r[0] * f[1] - r[1] * f[0]);
  else
    return AngVec<D>(Eigen::Vector3d(r).cross(Eigen::Vector3d(f)));
}

template <int D>
struct RigidBody {
  std::string name;
  BodyMotion motion = BodyMotion::kFree;
  MotionPath path;               // prescribed motion
  double body_force_factor = 1;  // 1 for gravity, (rho_s - rho_f)/rho_s buoyancy-reduced

  // Mass properties (eqs. 20-23): total mass, centre of mass, inertia in the body frame
  // (2D: about z), with particle self-inertia (Remark 13).
  double mass = 0;
  std::int64_t particles = 0;
  Vec<D> com0 = Vec<D>::Zero();  // centre of mass at t = 0 (prescribed motion)
  Eigen::Matrix<double, D == 2 ? 1 : 3, D == 2 ? 1 : 3> inertia_body;

  Orientation<D> orientation;
  Vec<D> com = Vec<D>::Zero();
  Vec<D> velocity = Vec<D>::Zero();
  AngVec<D> omega = AngVec<D>::Zero();
  AngVec<D> angular_momentum = AngVec<D>::Zero();  // world frame (3D)

  // Forces of the last evaluation: fluid coupling (eq. 19, summed by eqs. 24-26), contact
  // (eq. 27) and the body force.
  Vec<D> fluid_force = Vec<D>::Zero(), contact_force = Vec<D>::Zero();
  AngVec<D> fluid_torque = AngVec<D>::Zero(), contact_torque = AngVec<D>::Zero();
  // The fluid torque's part proportional to the body's own angular velocity: fluid_torque =
  // fluid_torque_rest + spin_damping omega, omega that of the evaluation. It is the symmetric
  // part of the viscous stress that a turning body receives (solver/physics/fluid_forces.h,
  // compute_solid_coupling): a damping, which the kick takes implicitly so that it cannot
  // overshoot however small the body's inertia (RigidBodies::kick).
  AngMat<D> spin_damping = AngMat<D>::Zero();
  AngVec<D> fluid_torque_rest = AngVec<D>::Zero();
  // The contact force averaged over the last fluid step (its impulse over dt). The body's
  // acceleration enters the fluid's wall condition (Adami 2012 eq. 27), which the fluid sees
  // once per step. With stiff contact the force at the end of a contact sub-step is a sample
  // of a vibration hundreds of times faster than the fluid step, and a collision is over within
  // one step: its mean acceleration (0.2 m/s reversed in 1e-4 s for a thrown disk) put into
  // eq. 27 turns into a suction of several times p0 under the rebounding body. The fluid
  // therefore sees the contact only as far as it holds the body against its other forces:
  // the mean contact force capped at the magnitude of fluid force plus body force. A body
  // resting on the floor then has a_w = 0 exactly, and the impulsive part of a collision
  // reaches the fluid through the body's velocity (the no-penetration and no-slip terms).
  // Measured: the instantaneous force blows up a settling pile of six disks (k_c = 1e8), the
  // uncapped mean a disk thrown at the floor; the capped mean runs both.
  Vec<D> mean_contact_force = Vec<D>::Zero();
  AngVec<D> mean_contact_torque = AngVec<D>::Zero();
  Vec<D> acceleration = Vec<D>::Zero();
  AngVec<D> angular_acceleration = AngVec<D>::Zero();
  std::int64_t contacts = 0;

  int source = -1;  // index of the case body it descends from (-1: born by solidification)
  // Its number in the order bodies were made (the case's 0..n-1, then each body a phase
  // transition makes): a slot that melting emptied goes to a later body, which the series
  // `bodies/serial` of the result tells apart. Its name is body_<serial> unless the case named it.
  std::int64_t serial = 0;

  // A body whose particles all melted (or that merged into another) leaves its slot empty.
  bool active() const { return particles > 0; }
  bool moves_freely() const { return motion == BodyMotion::kFree && active(); }
  // Whether forces move its centre of mass, and torques turn it.
  bool translates_freely() const {
    return active() && (motion == BodyMotion::kFree || motion == BodyMotion::kPrescribedRotation);
  }
  bool rotates_freely() const {
    return active() && (motion == BodyMotion::kFree || motion == BodyMotion::kPinned);
  }
  // Inverse mass against an impulse (0 where the translation is held), and the inverse
  // world-frame inertia (0 where the rotation is held).
  double inverse_mass() const { return translates_freely() ? 1.0 / mass : 0.0; }
  AngVec<D> inverse_inertia_if_free(const AngVec<D>& m) const {
    return rotates_freely() ? inverse_inertia(m) : AngVec<D>(AngVec<D>::Zero());
  }

  // World-frame inertia and its inverse applied to a vector.
  AngVec<D> inverse_inertia(const AngVec<D>& m) const {
    if constexpr (D == 2)
      return AngVec<D>(m[0] / inertia_body(0, 0));
    else {
      const Eigen::Matrix3d R = orientation.matrix();
      return R * inertia_body.ldlt().solve(R.transpose() * m);
    }
  }
  AngVec<D> world_inertia_times(const AngVec<D>& w) const {
    if constexpr (D == 2)
      return AngVec<D>(inertia_body(0, 0) * w[0]);
    else {
      const Eigen::Matrix3d R = orientation.matrix();
      return R * (inertia_body * (R.transpose() * w));
    }
  }
  // omega from the angular momentum at the current orientation (3D) or directly (2D).
  void update_omega() {
    if constexpr (D == 3) omega = inverse_inertia(angular_momentum);
  }
  double kinetic_energy() const {
    return 0.5 * mass * velocity.squaredNorm() + 0.5 * omega.dot(world_inertia_times(omega));
  }
};

}  // namespace sph
