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
  } else if (b.has_motion()) {
    error(cat(f, "motion"), "only used with motion_type: PRESCRIBED");
  }
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
  positive(k.stiffness(), "contact.stiffness");
  non_negative(k.damping(), "contact.damping");
  if (k.has_friction()) {
    non_negative(k.friction().coefficient(), "contact.friction.coefficient");
    positive(k.friction().tangential_stiffness(), "contact.friction.tangential_stiffness");
  }
  bool solidifies = false;
  for (const auto& pt : c_.phase_transitions()) solidifies = solidifies || pt.reversible();
  if (c_.bodies_size() == 0 && !solidifies)
    error("contact",
          "contact is configured but the case has no rigid bodies (and no reversible phase "
          "transition that could make some)");
}

}  // namespace sph::case_validation
