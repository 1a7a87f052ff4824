// Rigid bodies and the contact between them.
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::body(const v1::RigidBody& b, const std::string& f) {
  if (!b.has_shape())
    error(cat(f, "shape"), "is required");
  else
    shape(b.shape(), cat(f, "shape"), true);
  material_ref(b.material(), v1::SOLID, cat(f, "material"), true);
  if (!b.name().empty() && !body_names_.insert(b.name()).second)
    error(cat(f, "name"), "duplicate body name '" + b.name() + "'");
  vec(b.initial_velocity(), cat(f, "initial_velocity"));
  const auto& w = b.initial_angular_velocity();  // 2D: the z component is the rotation
  if (!finite(w.x()) || !finite(w.y()) || !finite(w.z()))
    error(cat(f, "initial_angular_velocity"), "must be finite");
  if (c_.dimension() == 2 &&
      (b.initial_angular_velocity().x() != 0 || b.initial_angular_velocity().y() != 0))
    error(cat(f, "initial_angular_velocity"), "a 2D body rotates about z only (x and y must be 0)");
  if (b.motion_type() == v1::PRESCRIBED) {
    if (!b.has_motion())
      error(cat(f, "motion"), "a PRESCRIBED body needs a motion");
    else
      motion(b.motion(), cat(f, "motion"));
  } else if (b.motion_type() == v1::PRESCRIBED_ROTATION) {
    const auto& m = b.motion();
    if (!b.has_motion() || !m.has_angular_velocity())
      error(cat(f, "motion.angular_velocity"),
            "a PRESCRIBED_ROTATION body needs motion.angular_velocity");
    else
      motion(m, cat(f, "motion"));
    if (m.has_velocity_x() || m.has_velocity_y() || m.has_velocity_z())
      error(cat(f, "motion"),
            "PRESCRIBED_ROTATION prescribes the rotation only (its translation is free): "
            "velocity_x, velocity_y and velocity_z must be unset");
    if (m.has_center())
      error(cat(f, "motion.center"),
            "PRESCRIBED_ROTATION turns the body about its centre of mass: center must be unset");
    if (b.has_initial_angular_velocity())
      error(cat(f, "initial_angular_velocity"),
            "PRESCRIBED_ROTATION takes its angular velocity from motion.angular_velocity");
  } else if (b.has_motion()) {
    error(cat(f, "motion"), "only used with motion_type: PRESCRIBED or PRESCRIBED_ROTATION");
  }
  if (b.motion_type() == v1::PINNED) {
    const auto& u = b.initial_velocity();
    if (u.x() != 0 || u.y() != 0 || u.z() != 0)
      error(cat(f, "initial_velocity"),
            "a PINNED body's centre of mass does not move: initial_velocity must be zero");
  }
  if ((b.motion_type() == v1::PINNED || b.motion_type() == v1::PRESCRIBED_ROTATION) &&
      c_.phase_transitions_size() > 0)
    error(cat(f, "motion_type"),
          "PINNED and PRESCRIBED_ROTATION bodies cannot be combined with phase_transitions "
          "(melting would split the pinned body; not supported)");
  if (b.body_force() == v1::BUOYANCY_REDUCED) {
    material_ref(b.buoyancy_fluid(), v1::FLUID, cat(f, "buoyancy_fluid"), true);
    if (!c_.has_gravity()) error(cat(f, "body_force"), "BUOYANCY_REDUCED needs gravity");
  } else if (!b.buoyancy_fluid().empty()) {
    error(cat(f, "buoyancy_fluid"), "only used with body_force: BUOYANCY_REDUCED");
  }
  if (b.has_initial_temperature() && !c_.has_thermal())
    error(cat(f, "initial_temperature"),
          "set, but heat conduction is not enabled (add a `thermal { }` block)");
  if (b.has_initial_concentration() && !c_.has_diffusion())
    error(cat(f, "initial_concentration"),
          "set, but concentration diffusion is not enabled (add a `diffusion { }` block)");
  transport_properties(b.material(), f + ".material");
}

void Validator::contact() {
  const auto& k = c_.contact();
  const auto model = k.model();
  if (!v1::ContactModel_IsValid(model)) {
    error("contact.model", "unknown contact model " + std::to_string(model));
    return;
  }
  const bool spring = model == v1::SPRING_DASHPOT || model == v1::CONTACT_MODEL_UNSPECIFIED;
  const std::string name = v1::ContactModel_Name(spring ? v1::SPRING_DASHPOT : model);
  if (spring) {
    positive(k.stiffness(), "contact.stiffness");
    non_negative(k.damping(), "contact.damping");
  } else {
    if (k.stiffness() != 0) error("contact.stiffness", "not used by the " + name + " model");
    if (k.damping() != 0) error("contact.damping", "not used by the " + name + " model");
  }
  if (k.has_restitution()) {
    const double e = k.restitution();
    if (model == v1::REPULSIVE)
      error("contact.restitution", "not used by the REPULSIVE model");
    else if (model == v1::RESTITUTION && !(e >= 0 && e <= 1))
      error("contact.restitution", "must be in [0, 1]; got " + num(e));
    else if (spring && !(e > 0 && e <= 1))
      error("contact.restitution",
            "must be in (0, 1] for the spring-dashpot (e = 0 needs an infinite dashpot); got " +
                num(e));
    if (spring && k.damping() != 0)
      error("contact.damping",
            "give either damping or restitution: restitution sets the dashpot of each pair");
  } else if (model == v1::RESTITUTION) {
    error("contact.restitution", "the RESTITUTION model needs a restitution in [0, 1]");
  }
  if (model == v1::REPULSIVE) {
    if (!k.has_repulsion()) {
      error("contact.repulsion", "the REPULSIVE model needs repulsion { strength range }");
    } else {
      positive(k.repulsion().strength(), "contact.repulsion.strength");
      const double delta = k.repulsion().range();
      if (!(delta > 0 && delta <= c_.dx()))
        error("contact.repulsion.range",
              "must be in (0, dx] = (0, " + num(c_.dx()) + "]; got " + num(delta));
    }
    if (k.has_friction()) error("contact.friction", "not used by the REPULSIVE model");
  } else if (k.has_repulsion()) {
    error("contact.repulsion", "only used by the REPULSIVE model");
  }
  if (k.has_friction() && model != v1::REPULSIVE) {
    non_negative(k.friction().coefficient(), "contact.friction.coefficient");
    if (model == v1::RESTITUTION) {
      if (k.friction().tangential_stiffness() != 0)
        error("contact.friction.tangential_stiffness",
              "not used by the RESTITUTION model (its friction is an impulse)");
    } else {
      positive(k.friction().tangential_stiffness(), "contact.friction.tangential_stiffness");
    }
  }
  bool solidifies = false;
  for (const auto& pt : c_.phase_transitions()) solidifies = solidifies || pt.reversible();
  if (c_.bodies_size() == 0 && !solidifies)
    error("contact",
          "contact is configured but the case has no rigid bodies (and no reversible phase "
          "transition that could make some)");
}

}  // namespace sph::case_validation
