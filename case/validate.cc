#include "case/validate.h"

#include "case/number_text.h"

#include <cmath>
#include <map>
#include <set>

#include "case/case_bounds.h"
#include "case/case_limits.h"
#include "case/estimate.h"
#include "case/geometry.h"
#include "case/lattice.h"
#include "case/validate_reference.h"
#include "case/wall_thickness.h"

namespace sph {
namespace {

std::string idx(const std::string& base, int i) {
  return base + "[" + std::to_string(i) + "]";
}
std::string cat(const std::string& base, const std::string& f) {
  return base.empty() ? f : base + "." + f;
}
bool finite(double v) {
  return std::isfinite(v);
}

class Validator {
 public:
  Validator(const v1::Case& c, const ValidationLimits& limits, CaseEstimate* estimate)
      : c_(c), limits_(limits), estimate_(estimate) {}

  std::vector<FieldError> run() {
    // The checks below recurse over shapes and do lattice arithmetic: only within the bounds.
    if (auto bounds = check_case_bounds(c_); !bounds.empty()) {
      for (auto& e : bounds) error(e.field, e.message);
      return reported();
    }
    top_level();
    if (dim_ok_) {
      materials();
      for (int i = 0; i < c_.fluids_size(); ++i) fluid(c_.fluids(i), idx("fluids", i));
      for (int i = 0; i < c_.walls_size(); ++i) wall(c_.walls(i), idx("walls", i));
      for (int i = 0; i < c_.bodies_size(); ++i) body(c_.bodies(i), idx("bodies", i));
      not_implemented();
      numerics();
      probes();
      size_limit();
    }
    return reported();
  }

  std::vector<FieldError> reported() {
    if (unreported_ > 0)
      errors_.push_back({"", "and " + std::to_string(unreported_) + " more error" +
                                 (unreported_ == 1 ? "" : "s") + " (only the first " +
                                 std::to_string(kMaxReportedErrors) + " are listed)"});
    return std::move(errors_);
  }

 private:
  void error(const std::string& field, const std::string& msg) {
    if (errors_.size() < static_cast<std::size_t>(kMaxReportedErrors))
      errors_.push_back({field, msg});
    else
      ++unreported_;
  }

  void positive(double v, const std::string& field, const std::string& what = "must be > 0") {
    if (!finite(v) || v <= 0) error(field, what + " (got " + num(v) + ")");
  }
  void non_negative(double v, const std::string& field) {
    if (!finite(v) || v < 0) error(field, "must be >= 0 (got " + num(v) + ")");
  }
  static std::string num(double v) { return number_text(v); }

  void vec(const v1::Vec3& v, const std::string& field) {
    if (!finite(v.x()) || !finite(v.y()) || !finite(v.z())) error(field, "must be finite");
    if (c_.dimension() == 2 && v.z() != 0.0)
      error(cat(field, "z"), "must be 0 in a 2D case (got " + num(v.z()) + ")");
  }

  // A position or length of a shape: finite (vec() and positive() name that) and within
  // kMaxCoordinate, so that its squares and the lattice walk over its bounds stay finite.
  void extent(double v, const std::string& field) {
    if (finite(v) && std::abs(v) > kMaxCoordinate)
      error(field, "is " + count_text(v) + " m; coordinates and lengths must lie within +-" +
                       count_text(kMaxCoordinate) + " m");
  }
  // Whether point() finds nothing wrong; a point set of millions names only the points that
  // are wrong, not build each one's field path.
  bool point_ok(const v1::Vec3& v) const {
    auto ok = [](double x) { return finite(x) && std::abs(x) <= kMaxCoordinate; };
    return ok(v.x()) && ok(v.y()) && (c_.dimension() == 2 ? v.z() == 0.0 : ok(v.z()));
  }
  void point(const v1::Vec3& v, const std::string& field) {
    vec(v, field);
    extent(v.x(), cat(field, "x"));
    extent(v.y(), cat(field, "y"));
    if (c_.dimension() == 3) extent(v.z(), cat(field, "z"));
  }

  void top_level() {
    if (c_.dimension() != 2 && c_.dimension() != 3) {
      error("dimension", "must be 2 or 3 (got " + std::to_string(c_.dimension()) + ")");
      dim_ok_ = false;
      return;
    }
    positive(c_.dx(), "dx");
    if (c_.has_smoothing_length_ratio() &&
        !(c_.smoothing_length_ratio() >= 1.0 && c_.smoothing_length_ratio() <= 4.0))
      error("smoothing_length_ratio",
            "must be between 1 and 4 (got " + num(c_.smoothing_length_ratio()) + ")");
    if (c_.has_neighbor_skin() && !(c_.neighbor_skin() >= 0.0 && c_.neighbor_skin() <= 2.0))
      error("neighbor_skin",
            "must be between 0 and 2 (times dx; got " + num(c_.neighbor_skin()) + ")");
    if (!c_.has_domain()) {
      error("domain", "is required (the bounding box of the computational domain)");
    } else {
      vec(c_.domain().lo(), "domain.lo");
      vec(c_.domain().hi(), "domain.hi");
      const char* axes = "xyz";
      for (int a = 0; a < c_.dimension(); ++a) {
        const double lo = a == 0   ? c_.domain().lo().x()
                          : a == 1 ? c_.domain().lo().y()
                                   : c_.domain().lo().z();
        const double hi = a == 0   ? c_.domain().hi().x()
                          : a == 1 ? c_.domain().hi().y()
                                   : c_.domain().hi().z();
        if (!(hi > lo))
          error(std::string("domain.hi.") + axes[a],
                "must be greater than domain.lo." + std::string(1, axes[a]));
        else if (c_.dx() > 0 && (hi - lo) < 2 * kernel_support_radius(c_))
          error(std::string("domain.hi.") + axes[a],
                "domain is narrower than two kernel supports along " + std::string(1, axes[a]));
      }
    }
    if (c_.dimension() == 2 && c_.periodic_z()) error("periodic_z", "not allowed in a 2D case");
    vec(c_.lattice_origin(), "lattice_origin");
    if (c_.fluids_size() == 0 && c_.bodies_size() == 0)
      error("fluids", "a case needs at least one fluid region or rigid body");
  }

  void materials() {
    for (int i = 0; i < c_.materials_size(); ++i) {
      const auto& m = c_.materials(i);
      const std::string f = idx("materials", i);
      if (m.name().empty())
        error(cat(f, "name"), "must not be empty");
      else if (!names_.insert(m.name()).second)
        error(cat(f, "name"), "duplicate material name '" + m.name() + "'");
      phase_[m.name()] = m.phase() == v1::SOLID ? v1::SOLID : v1::FLUID;
      positive(m.density(), cat(f, "density"));
      if (m.phase() != v1::SOLID) {
        const auto& e = m.eos();
        const std::string ef = cat(f, "eos");
        if (e.has_sound_speed() == e.has_reference_pressure())
          error(ef, "give exactly one of sound_speed and reference_pressure");
        if (e.has_sound_speed()) positive(e.sound_speed(), cat(ef, "sound_speed"));
        if (e.has_reference_pressure())
          positive(e.reference_pressure(), cat(ef, "reference_pressure"));
        if (e.has_gamma()) {
          positive(e.gamma(), cat(ef, "gamma"));
          if (e.kind() != v1::TAIT) error(cat(ef, "gamma"), "only used with kind: TAIT");
        }
        if (!finite(e.background_pressure()))
          error(cat(ef, "background_pressure"), "must be finite");
        if (m.has_dynamic_viscosity() && m.has_kinematic_viscosity())
          error(f, "give at most one of dynamic_viscosity and kinematic_viscosity");
        if (m.has_dynamic_viscosity())
          non_negative(m.dynamic_viscosity(), cat(f, "dynamic_viscosity"));
        if (m.has_kinematic_viscosity())
          non_negative(m.kinematic_viscosity(), cat(f, "kinematic_viscosity"));
        if (m.has_transport_background_pressure()) {
          non_negative(m.transport_background_pressure(), cat(f, "transport_background_pressure"));
          if (!c_.fluid_model().transport_velocity())
            error(cat(f, "transport_background_pressure"),
                  "set, but fluid_model.transport_velocity is not enabled");
        }
      } else if (m.has_eos()) {
        error(cat(f, "eos"), "a SOLID material has no equation of state");
      }
      // Thermal and diffusion properties: checked against the effects the case enables.
      if (m.has_heat_capacity()) positive(m.heat_capacity(), cat(f, "heat_capacity"));
      if (m.has_thermal_conductivity())
        non_negative(m.thermal_conductivity(), cat(f, "thermal_conductivity"));
      if (m.has_diffusivity()) non_negative(m.diffusivity(), cat(f, "diffusivity"));
      if (!c_.has_thermal() && (m.has_heat_capacity() || m.has_thermal_conductivity()))
        error(cat(f, m.has_heat_capacity() ? "heat_capacity" : "thermal_conductivity"),
              "set, but heat conduction is not enabled (add a `thermal { }` block)");
      if (!c_.has_diffusion() && (m.has_diffusivity() || m.fixed_concentration()))
        error(cat(f, m.has_diffusivity() ? "diffusivity" : "fixed_concentration"),
              "set, but concentration diffusion is not enabled (add a `diffusion { }` block)");
    }
  }

  static constexpr int kMaterialsListed = 8;
  void material_ref(const std::string& name, v1::MaterialPhase want, const std::string& field,
                    bool required) {
    if (name.empty()) {
      if (required) error(field, "is required");
      return;
    }
    auto it = phase_.find(name);
    if (it == phase_.end()) {
      // A few names are enough to spot a typo; all of them, in each of a thousand such errors,
      // would be megabytes.
      std::string known;
      int listed = 0;
      for (const auto& n : names_) {
        if (listed == kMaterialsListed) {
          known += " and " + std::to_string(names_.size() - listed) + " more";
          break;
        }
        known += (known.empty() ? "" : ", ") + n;
        ++listed;
      }
      error(field,
            "unknown material '" + name + "' (defined: " + (known.empty() ? "none" : known) + ")");
    } else if (it->second != want) {
      error(field, "material '" + name + "' is " + (it->second == v1::SOLID ? "SOLID" : "FLUID") +
                       ", expected " + (want == v1::SOLID ? "SOLID" : "FLUID"));
    }
  }

  void shape(const v1::Shape& s, const std::string& f, bool top) {
    const int d = c_.dimension();
    switch (s.kind_case()) {
      case v1::Shape::KIND_NOT_SET:
        error(f,
              "shape has no kind (box, ball, cylinder, polygon, polar_curve, points, union, "
              "intersection, difference or shell)");
        break;
      case v1::Shape::kBox: {
        point(s.box().lo(), cat(f, "box.lo"));
        point(s.box().hi(), cat(f, "box.hi"));
        const double lo[3] = {s.box().lo().x(), s.box().lo().y(), s.box().lo().z()};
        const double hi[3] = {s.box().hi().x(), s.box().hi().y(), s.box().hi().z()};
        for (int a = 0; a < d; ++a)
          if (!(hi[a] > lo[a]))
            error(cat(f, std::string("box.hi.") + "xyz"[a]), "must be greater than box.lo");
        break;
      }
      case v1::Shape::kBall:
        point(s.ball().center(), cat(f, "ball.center"));
        positive(s.ball().radius(), cat(f, "ball.radius"));
        extent(s.ball().radius(), cat(f, "ball.radius"));
        break;
      case v1::Shape::kCylinder:
        if (d != 3) error(cat(f, "cylinder"), "only in 3D cases (use ball or box in 2D)");
        point(s.cylinder().base(), cat(f, "cylinder.base"));
        point(s.cylinder().axis(), cat(f, "cylinder.axis"));
        positive(s.cylinder().radius(), cat(f, "cylinder.radius"));
        positive(s.cylinder().length(), cat(f, "cylinder.length"));
        extent(s.cylinder().radius(), cat(f, "cylinder.radius"));
        extent(s.cylinder().length(), cat(f, "cylinder.length"));
        if (s.cylinder().axis().x() == 0 && s.cylinder().axis().y() == 0 &&
            s.cylinder().axis().z() == 0)
          error(cat(f, "cylinder.axis"), "must not be zero");
        break;
      case v1::Shape::kPolygon:
        if (d != 2) error(cat(f, "polygon"), "only in 2D cases");
        if (s.polygon().vertices_size() < 3)
          error(cat(f, "polygon.vertices"), "needs at least 3 vertices");
        for (int i = 0; i < s.polygon().vertices_size(); ++i)
          if (!point_ok(s.polygon().vertices(i)))
            point(s.polygon().vertices(i), idx(cat(f, "polygon.vertices"), i));
        break;
      case v1::Shape::kPolarCurve: {
        const auto& p = s.polar_curve();
        if (d != 2) error(cat(f, "polar_curve"), "only in 2D cases");
        point(p.center(), cat(f, "polar_curve.center"));
        positive(p.radius(), cat(f, "polar_curve.radius"));
        extent(p.radius(), cat(f, "polar_curve.radius"));
        if (!(std::abs(p.amplitude()) < p.radius()))
          error(cat(f, "polar_curve.amplitude"), "|amplitude| must be less than radius");
        if (p.periods() < 0) error(cat(f, "polar_curve.periods"), "must be >= 0");
        break;
      }
      case v1::Shape::kPoints:
        if (!top) error(cat(f, "points"), "a point set can only be a top-level shape");
        if (!s.points().file().empty())
          error(cat(f, "points.file"),
                "point files must be inlined before validation (sphctl and sph-worker do this)");
        else if (s.points().points_size() == 0)
          error(cat(f, "points.points"), "is empty");
        for (int i = 0; i < s.points().points_size(); ++i)
          if (!point_ok(s.points().points(i)))
            point(s.points().points(i), idx(cat(f, "points.points"), i));
        break;
      case v1::Shape::kUnion:
      case v1::Shape::kIntersection: {
        const bool u = s.kind_case() == v1::Shape::kUnion;
        const auto& l = u ? s.union_() : s.intersection();
        const std::string lf = cat(f, u ? "union.shapes" : "intersection.shapes");
        if (l.shapes_size() == 0) error(lf, "is empty");
        for (int i = 0; i < l.shapes_size(); ++i) shape(l.shapes(i), idx(lf, i), false);
        break;
      }
      case v1::Shape::kDifference:
        if (!s.difference().has_base())
          error(cat(f, "difference.base"), "is required");
        else
          shape(s.difference().base(), cat(f, "difference.base"), false);
        for (int i = 0; i < s.difference().subtract_size(); ++i)
          shape(s.difference().subtract(i), idx(cat(f, "difference.subtract"), i), false);
        break;
      case v1::Shape::kShell:
        if (!s.shell().has_inner())
          error(cat(f, "shell.inner"), "is required");
        else
          shape(s.shell().inner(), cat(f, "shell.inner"), false);
        if (s.shell().has_thickness()) {
          positive(s.shell().thickness(), cat(f, "shell.thickness"));
          extent(s.shell().thickness(), cat(f, "shell.thickness"));
        }
        break;
    }
  }

  void time_function(const v1::TimeFunction& tf, const std::string& f) {
    switch (tf.kind_case()) {
      case v1::TimeFunction::kConstant:
        if (!finite(tf.constant())) error(cat(f, "constant"), "must be finite");
        break;
      case v1::TimeFunction::kSine:
        if (!finite(tf.sine().amplitude()) || !finite(tf.sine().angular_frequency()) ||
            !finite(tf.sine().offset()) || !finite(tf.sine().phase()))
          error(cat(f, "sine"), "all parameters must be finite");
        break;
      case v1::TimeFunction::kPiecewiseLinear:
      case v1::TimeFunction::kPiecewiseConstant: {
        const bool lin = tf.kind_case() == v1::TimeFunction::kPiecewiseLinear;
        const auto& t = lin ? tf.piecewise_linear() : tf.piecewise_constant();
        const std::string tfld = cat(f, lin ? "piecewise_linear" : "piecewise_constant");
        if (t.times_size() == 0) error(cat(tfld, "times"), "is empty");
        if (t.times_size() != t.values_size())
          error(cat(tfld, "values"),
                "needs as many values as times (" + std::to_string(t.times_size()) + ")");
        for (int i = 1; i < t.times_size(); ++i)
          if (!(t.times(i) > t.times(i - 1)))
            error(idx(cat(tfld, "times"), i), "times must be strictly increasing");
        break;
      }
      case v1::TimeFunction::KIND_NOT_SET:
        break;
    }
    non_negative(tf.start_time(), cat(f, "start_time"));
    if (tf.end_time() != 0 && tf.end_time() <= tf.start_time())
      error(cat(f, "end_time"), "must be greater than start_time (or 0 for never)");
  }

  void motion(const v1::Motion& m, const std::string& f) {
    time_function(m.velocity_x(), cat(f, "velocity_x"));
    time_function(m.velocity_y(), cat(f, "velocity_y"));
    if (c_.dimension() == 2 && m.has_velocity_z())
      error(cat(f, "velocity_z"), "not allowed in a 2D case");
    time_function(m.velocity_z(), cat(f, "velocity_z"));
    time_function(m.angular_velocity(), cat(f, "angular_velocity"));
    vec(m.center(), cat(f, "center"));
    vec(m.axis(), cat(f, "axis"));
    if (c_.dimension() == 3 && m.has_angular_velocity() && m.axis().x() == 0 && m.axis().y() == 0 &&
        m.axis().z() == 0)
      error(cat(f, "axis"), "a 3D rotation needs a non-zero axis");
  }

  void fluid(const v1::FluidRegion& r, const std::string& f) {
    material_ref(r.material(), v1::FLUID, cat(f, "material"), true);
    if (!r.has_shape())
      error(cat(f, "shape"), "is required");
    else
      shape(r.shape(), cat(f, "shape"), true);
    vec(r.initial_velocity(), cat(f, "initial_velocity"));
    if (r.initial_velocity_field().has_taylor_green()) {
      const auto& tg = r.initial_velocity_field().taylor_green();
      if (c_.dimension() != 2)
        error(cat(f, "initial_velocity_field.taylor_green"), "only in 2D cases");
      positive(tg.wavelength(), cat(f, "initial_velocity_field.taylor_green.wavelength"));
      if (!finite(tg.amplitude()))
        error(cat(f, "initial_velocity_field.taylor_green.amplitude"), "must be finite");
    }
    if (r.initial_velocity_field().has_linear()) {
      const auto& lf = r.initial_velocity_field().linear();
      const std::string g = cat(f, "initial_velocity_field.linear");
      vec(lf.center(), cat(g, "center"));
      vec(lf.gradient_x(), cat(g, "gradient_x"));
      vec(lf.gradient_y(), cat(g, "gradient_y"));
      if (c_.dimension() == 2 &&
          (lf.gradient_z().x() != 0 || lf.gradient_z().y() != 0 || lf.gradient_z().z() != 0))
        error(cat(g, "gradient_z"), "must be 0 in 2D cases");
      else if (c_.dimension() == 3)
        vec(lf.gradient_z(), cat(g, "gradient_z"));
    }
    if (!(r.position_jitter() >= 0 && r.position_jitter() <= 0.5))
      error(cat(f, "position_jitter"), "must be in [0, 0.5] (a fraction of dx)");
    if (r.has_hydrostatic_surface()) {
      if (!finite(r.hydrostatic_surface())) error(cat(f, "hydrostatic_surface"), "must be finite");
      if (!c_.has_gravity()) error(cat(f, "hydrostatic_surface"), "needs gravity");
    }
    if (r.has_initial_temperature() && !c_.has_thermal())
      error(cat(f, "initial_temperature"),
            "set, but heat conduction is not enabled (add a `thermal { }` block)");
    if (r.has_initial_concentration() && !c_.has_diffusion())
      error(cat(f, "initial_concentration"),
            "set, but concentration diffusion is not enabled (add a `diffusion { }` block)");
    transport_properties(r.material(), f + ".material");
  }

  // Every material that conducts or diffuses needs its coefficients once the effect is on.
  void transport_properties(const std::string& name, const std::string& field) {
    const int k = material_position(name);
    if (k < 0) return;
    const auto& m = c_.materials(k);
    const std::string mf = idx("materials", k);
    if (c_.has_thermal() && (!m.has_heat_capacity() || !m.has_thermal_conductivity()) &&
        reported_.insert(mf + "t").second)
      error(cat(mf, m.has_heat_capacity() ? "thermal_conductivity" : "heat_capacity"),
            "required: heat conduction is enabled and material '" + name + "' is used by " + field);
    if (c_.has_diffusion() && !m.has_diffusivity() && reported_.insert(mf + "d").second)
      error(cat(mf, "diffusivity"), "required: concentration diffusion is enabled and material '" +
                                        name + "' is used by " + field);
  }
  int material_position(const std::string& name) const {
    for (int k = 0; k < c_.materials_size(); ++k)
      if (c_.materials(k).name() == name) return k;
    return -1;
  }

  void wall(const v1::Wall& w, const std::string& f) {
    if (!w.has_shape())
      error(cat(f, "shape"), "is required");
    else
      shape(w.shape(), cat(f, "shape"), true);
    material_ref(w.material(), v1::SOLID, cat(f, "material"), false);
    if (w.has_motion()) motion(w.motion(), cat(f, "motion"));
    if (w.has_temperature()) {
      if (!c_.has_thermal())
        error(cat(f, "temperature"),
              "set, but heat conduction is not enabled (add a `thermal { }` block)");
      time_function(w.temperature().value(), cat(f, "temperature.value"));
    }
    if (w.has_concentration()) {
      if (!c_.has_diffusion())
        error(cat(f, "concentration"),
              "set, but concentration diffusion is not enabled (add a `diffusion { }` block)");
      time_function(w.concentration().value(), cat(f, "concentration.value"));
    }
    if (!w.material().empty() && (w.has_temperature() || w.has_concentration()))
      transport_properties(w.material(), f + ".material");
  }

  void body(const v1::RigidBody& b, const std::string& f) {
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
      error(cat(f, "initial_angular_velocity"),
            "a 2D body rotates about z only (x and y must be 0)");
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

  void contact() {
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

  void phase_transitions() {
    for (int i = 0; i < c_.phase_transitions_size(); ++i) {
      const auto& pt = c_.phase_transitions(i);
      const std::string f = idx("phase_transitions", i);
      material_ref(pt.solid_material(), v1::SOLID, cat(f, "solid_material"), true);
      material_ref(pt.fluid_material(), v1::FLUID, cat(f, "fluid_material"), true);
      // A transition's materials conduct (diffuse) like any region's, even before a particle
      // of them exists (the melt of a scene that starts solid).
      transport_properties(pt.solid_material(), cat(f, "solid_material"));
      transport_properties(pt.fluid_material(), cat(f, "fluid_material"));
      // A particle keeps its mass when it changes phase (Fuchs 2021 eq. 29; all the paper's
      // examples give both phases one density): with two densities the melt would start
      // compressed or stretched by their ratio, an EOS pressure jump at every transition.
      const int ks = material_position(pt.solid_material()),
                kf = material_position(pt.fluid_material());
      if (ks >= 0 && kf >= 0 && c_.materials(ks).density() != c_.materials(kf).density())
        error(cat(f, "fluid_material"),
              "density " + num(c_.materials(kf).density()) + " of '" + pt.fluid_material() +
                  "' differs from the solid's " + num(c_.materials(ks).density()) + " ('" +
                  pt.solid_material() +
                  "'): a particle keeps its mass when it changes phase, so both materials need "
                  "the same density");
      if (pt.driver() == v1::DRIVER_UNSPECIFIED)
        error(cat(f, "driver"), "is required (TEMPERATURE or CONCENTRATION)");
      // A transition needs the field that drives it (issue: only the effects a scene calls for).
      if (pt.driver() == v1::TEMPERATURE && !c_.has_thermal())
        error(cat(f, "driver"),
              "TEMPERATURE needs heat conduction: add a `thermal { }` block to the case");
      if (pt.driver() == v1::CONCENTRATION && !c_.has_diffusion())
        error(cat(f, "driver"),
              "CONCENTRATION needs concentration diffusion: add a `diffusion { }` block");
      if (!finite(pt.transition_value())) error(cat(f, "transition_value"), "must be finite");
      non_negative(pt.hysteresis(), cat(f, "hysteresis"));
      if (pt.has_join_radius()) positive(pt.join_radius(), cat(f, "join_radius"));
      // Particles of a body link when closer than the join radius; at dx or less lattice
      // neighbours do not, and every body a transition touches falls apart into single particles.
      if (pt.has_join_radius() && pt.join_radius() > 0 && pt.join_radius() <= 1.01 * c_.dx())
        error(cat(f, "join_radius"),
              "must be larger than dx (" + num(c_.dx()) +
                  "): particles one lattice spacing apart must link, or every body a transition "
                  "touches breaks into single particles (default 1.5 dx)");
      if (pt.has_join_radius() && pt.join_radius() >= kernel_support_radius(c_))
        error(cat(f, "join_radius"), "must be smaller than the kernel support radius (" +
                                         num(kernel_support_radius(c_)) + ")");
      if (pt.has_max_bodies() && pt.max_bodies() < c_.bodies_size())
        error(cat(f, "max_bodies"), "must be >= the number of bodies in the case (" +
                                        std::to_string(c_.bodies_size()) + ")");
      if (pt.has_latent_heat() || pt.has_latent_heat_interval()) {
        if (pt.driver() == v1::CONCENTRATION)
          error(cat(f, pt.has_latent_heat() ? "latent_heat" : "latent_heat_interval"),
                "latent heat needs driver TEMPERATURE");
        if (!pt.has_latent_heat())
          error(cat(f, "latent_heat"), "is required with latent_heat_interval");
        else
          positive(pt.latent_heat(), cat(f, "latent_heat"));
        // The apparent capacity L/dT needs an interval of finite width (Fuchs 2021 Remark 3).
        if (!pt.has_latent_heat_interval())
          error(cat(f, "latent_heat_interval"),
                "is required with latent_heat (the temperature interval over which it is "
                "absorbed, centred on transition_value)");
        else
          positive(pt.latent_heat_interval(), cat(f, "latent_heat_interval"));
      }
      for (int j = 0; j < i; ++j)
        if (c_.phase_transitions(j).solid_material() == pt.solid_material() ||
            c_.phase_transitions(j).fluid_material() == pt.fluid_material())
          error(f, "a material takes part in two phase transitions (also in phase_transitions[" +
                       std::to_string(j) + "])");
    }
  }

  // Buffer zones (solver/boundaries/open_boundaries.h): a box in the domain, one layer of
  // whole particle rows at least r_c thick along a non-periodic coordinate axis.
  void open_boundaries() {
    const int d = c_.dimension();
    const char* axes = "xyz";
    std::set<std::string> seen;
    auto comp = [](const v1::Vec3& v, int a) { return a == 0 ? v.x() : a == 1 ? v.y() : v.z(); };
    const double rc = kernel_support_radius(c_);
    for (int i = 0; i < c_.open_boundaries_size(); ++i) {
      const auto& o = c_.open_boundaries(i);
      const std::string f = idx("open_boundaries", i);
      if (o.name().empty())
        error(cat(f, "name"), "must not be empty");
      else if (o.name().find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789_-") != std::string::npos)
        error(cat(f, "name"), "may contain only letters, digits, '_' and '-' (it names a series)");
      else if (!seen.insert(o.name()).second)
        error(cat(f, "name"), "duplicate open boundary name '" + o.name() + "'");
      const bool inflow = o.kind() == v1::INFLOW;
      if (o.kind() != v1::INFLOW && o.kind() != v1::OUTFLOW)
        error(cat(f, "kind"), "is required (INFLOW or OUTFLOW)");
      material_ref(o.material(), v1::FLUID, cat(f, "material"), true);
      transport_properties(o.material(), f + ".material");

      // Flow direction: one axis, not periodic.
      vec(o.direction(), cat(f, "direction"));
      int axis = -1, nonzero = 0;
      for (int a = 0; a < d; ++a)
        if (comp(o.direction(), a) != 0.0) {
          axis = a;
          ++nonzero;
        }
      if (nonzero != 1) {
        error(cat(f, "direction"),
              nonzero == 0 ? std::string("must not be zero")
                           : "must be along a coordinate axis (exactly one non-zero component); "
                             "oblique open boundaries are not supported");
        axis = -1;
      } else if ((axis == 0 && c_.periodic_x()) || (axis == 1 && c_.periodic_y()) ||
                 (axis == 2 && c_.periodic_z())) {
        error(cat(f, "direction"), std::string("the flow axis ") + axes[axis] +
                                       " is periodic (periodic_" + axes[axis] +
                                       "); an open boundary needs a non-periodic axis");
      }

      // The buffer region.
      if (!o.has_region()) {
        error(cat(f, "region"), "is required (the buffer zone)");
      } else {
        const auto& r = o.region();
        vec(r.lo(), cat(f, "region.lo"));
        vec(r.hi(), cat(f, "region.hi"));
        bool ok = true;
        for (int a = 0; a < d; ++a) {
          const double lo = comp(r.lo(), a), hi = comp(r.hi(), a);
          const std::string lf = cat(f, std::string("region.lo.") + axes[a]),
                            hf = cat(f, std::string("region.hi.") + axes[a]);
          if (!(hi > lo)) {
            error(hf, "must be greater than region.lo." + std::string(1, axes[a]));
            ok = false;
            continue;
          }
          if (c_.has_domain()) {
            const double dlo = comp(c_.domain().lo(), a), dhi = comp(c_.domain().hi(), a);
            const double tol = 1e-9 * (dhi - dlo);
            if (lo < dlo - tol)
              error(lf, "the region must lie in the domain (domain.lo." + std::string(1, axes[a]) +
                            " = " + num(dlo) + ", got " + num(lo) + ")");
            if (hi > dhi + tol)
              error(hf, "the region must lie in the domain (domain.hi." + std::string(1, axes[a]) +
                            " = " + num(dhi) + ", got " + num(hi) + ")");
          }
          if (c_.dx() <= 0) continue;
          if (a == axis) {
            if (hi - lo < rc * (1 - 1e-9))
              error(hf, "the buffer is " + num(hi - lo) +
                            " thick along the flow; it must be at "
                            "least the kernel support radius r_c = " +
                            num(rc) + " so that the fluid at the face has full support");
            const double org = comp(c_.lattice_origin(), a);
            for (const auto& [v, fld] : {std::pair{lo, lf}, std::pair{hi, hf}}) {
              const double k = (v - org) / c_.dx();
              if (std::abs(k - std::round(k)) > 1e-6)
                error(fld, "must lie on a lattice cell face (lattice_origin." +
                               std::string(1, axes[a]) +
                               " + k dx) so that the buffer holds whole "
                               "layers of particles (got " +
                               num(v) + ")");
            }
          } else if (axis >= 0 && hi - lo < c_.dx()) {
            error(hf, "the region is narrower than dx across the flow: it holds no particles");
          }
        }
        // Buffers must not overlap: a particle belongs to one.
        for (int j = 0; ok && j < i; ++j) {
          const auto& q = c_.open_boundaries(j).region();
          bool overlap = true;
          for (int a = 0; a < d; ++a)
            overlap =
                overlap && comp(r.lo(), a) < comp(q.hi(), a) && comp(q.lo(), a) < comp(r.hi(), a);
          if (overlap)
            error(cat(f, "region"), "overlaps open_boundaries[" + std::to_string(j) + "].region");
        }
      }

      // What drives it.
      const bool velocity = inflow || o.has_mean_velocity();
      if (inflow && !o.has_mean_velocity())
        error(cat(f, "mean_velocity"), "is required for an INFLOW");
      if (o.has_mean_velocity()) positive(o.mean_velocity(), cat(f, "mean_velocity"));
      if (velocity) {
        non_negative(o.start_time(), cat(f, "start_time"));
        non_negative(o.ramp_time(), cat(f, "ramp_time"));
      } else {
        const std::string why = "only used with mean_velocity (a velocity outlet or an inflow)";
        if (o.profile() != v1::PROFILE_UNSPECIFIED) error(cat(f, "profile"), why);
        if (o.start_time() != 0) error(cat(f, "start_time"), why);
        if (o.ramp_time() != 0) error(cat(f, "ramp_time"), why);
      }
      if (o.has_pressure()) {
        if (velocity)
          error(cat(f, "pressure"),
                "only used by a pressure outlet (an OUTFLOW without mean_velocity); where the "
                "velocity is prescribed the pressure follows from the fluid");
        else if (!finite(o.pressure()))
          error(cat(f, "pressure"), "must be finite");
      }
      if (o.has_temperature()) {
        if (!inflow) error(cat(f, "temperature"), "only used by an INFLOW");
        if (!c_.has_thermal())
          error(cat(f, "temperature"),
                "set, but heat conduction is not enabled (add a `thermal { }` block)");
      }
      if (o.has_concentration()) {
        if (!inflow) error(cat(f, "concentration"), "only used by an INFLOW");
        if (!c_.has_diffusion())
          error(cat(f, "concentration"),
                "set, but concentration diffusion is not enabled (add a `diffusion { }` block)");
      }
    }
  }

  void not_implemented() {
    if (c_.has_contact()) contact();
    phase_transitions();
    if (c_.has_thermal()) {
      if (!finite(c_.thermal().initial_temperature()))
        error("thermal.initial_temperature", "must be finite");
      if (!finite(c_.thermal().volumetric_heat_source()))
        error("thermal.volumetric_heat_source", "must be finite");
    }
    open_boundaries();
    for (auto& e : validate_reference(c_)) errors_.push_back(std::move(e));
  }

  void numerics() {
    const auto& fm = c_.fluid_model();
    non_negative(fm.artificial_viscosity(), "fluid_model.artificial_viscosity");
    if (c_.has_gravity()) {
      vec(c_.gravity().acceleration(), "gravity.acceleration");
      non_negative(c_.gravity().damping_time(), "gravity.damping_time");
    }
    vec(c_.body_force(), "body_force");
    const auto& t = c_.time();
    positive(t.end_time(), "time.end_time");
    if (t.has_cfl_factor() && (!(t.cfl_factor() > 0) || t.cfl_factor() > 2))
      error("time.cfl_factor", "must be in (0, 2] (got " + num(t.cfl_factor()) + ")");
    non_negative(t.fixed_dt(), "time.fixed_dt");
    // A fluid material a phase transition produces gives the bound its sound speed too.
    if (c_.fluids_size() == 0 && c_.phase_transitions_size() == 0 && !(t.fixed_dt() > 0))
      error("time.fixed_dt",
            "is required when the case has no fluid (the bound of Fuchs 2021 eq. 41 needs a sound "
            "speed)");
    if (t.max_steps() < 0) error("time.max_steps", "must be >= 0");
    const auto& o = c_.output();
    non_negative(o.interval(), "output.interval");
    // Every snapshot time is stored up front and each snapshot is a full particle dump.
    constexpr double kMaxSnapshots = 100000;
    if (o.interval() > 0 && t.end_time() > 0 && t.end_time() / o.interval() > kMaxSnapshots)
      error("output.interval", "gives " + num(t.end_time() / o.interval()) +
                                   " snapshots (end_time / interval); at most 100000 are allowed");
    non_negative(o.series_interval(), "output.series_interval");
    non_negative(o.checkpoint_wall_interval(), "output.checkpoint_wall_interval");
    for (int i = 0; i < o.times_size(); ++i)
      if (!(o.times(i) >= 0) || o.times(i) > t.end_time())
        error(idx("output.times", i), "must be within [0, time.end_time]");
    const auto& g = c_.guards();
    if (g.has_max_density_deviation())
      positive(g.max_density_deviation(), "guards.max_density_deviation");
    if (g.has_min_dt_fraction()) positive(g.min_dt_fraction(), "guards.min_dt_fraction");
    if (g.has_max_mach()) positive(g.max_mach(), "guards.max_mach");
    if (g.has_max_solid_fraction() && (!(g.max_solid_fraction() > 0) || g.max_solid_fraction() > 1))
      error("guards.max_solid_fraction",
            "must be in (0, 1] (got " + num(g.max_solid_fraction()) + ")");
    if (g.has_max_contact_substeps() && g.max_contact_substeps() < 1)
      error("guards.max_contact_substeps", "must be >= 1");
    non_negative(c_.stop().max_wall_seconds(), "stop.max_wall_seconds");
    non_negative(c_.stop().steady_kinetic_energy(), "stop.steady_kinetic_energy");
  }

  void probes() {
    std::set<std::string> seen;
    for (int i = 0; i < c_.probes_size(); ++i) {
      const auto& p = c_.probes(i);
      const std::string f = idx("probes", i);
      if (p.name().empty())
        error(cat(f, "name"), "must not be empty");
      else if (!seen.insert(p.name()).second)
        error(cat(f, "name"), "duplicate probe name '" + p.name() + "'");
      vec(p.position(), cat(f, "position"));
      vec(p.line_end(), cat(f, "line_end"));
      if (p.count() < 0 || p.count() > 10000) error(cat(f, "count"), "must be in [0, 10000]");
    }
  }

  // Each region must place particles, and a fluid or a body most of them inside the domain
  // (kMinRegionFractionInDomain): the scene builder drops whatever lies outside without a word.
  // The regions share kRegionCheckWork; one counted on a sample is refused for lying outside
  // only when the sample is large enough to tell, and never for placing no particles (a thin
  // region can slip between the points of a sample).
  void regions_in_domain() {
    const int d = c_.dimension();
    const LatticeSpec spec{d, c_.dx(), to_point(c_.lattice_origin())};
    Aabb domain{to_point(c_.domain().lo()), to_point(c_.domain().hi())};
    if (d == 2) domain.lo.z() = domain.hi.z() = 0.0;
    // Lattice points around the domain, as far again as the domain is wide on each side of a
    // non-periodic axis: a finite box (the lattice range check covers it) that holds any region
    // "mostly" inside. Along a periodic axis the domain clips every region on purpose.
    Aabb around = domain;
    const bool periodic[3] = {c_.periodic_x(), c_.periodic_y(), c_.periodic_z()};
    for (int a = 0; a < d; ++a) {
      if (periodic[a]) continue;
      const double w = domain.hi[a] - domain.lo[a];
      around.lo[a] -= w;
      around.hi[a] += w;
    }
    struct Region {
      const v1::Shape* shape;
      std::string kind, name, field;
    };
    std::vector<Region> regions;
    for (int i = 0; i < c_.fluids_size(); ++i)
      regions.push_back(
          {&c_.fluids(i).shape(), "fluid", c_.fluids(i).name(), cat(idx("fluids", i), "shape")});
    for (int i = 0; i < c_.walls_size(); ++i)
      regions.push_back(
          {&c_.walls(i).shape(), "wall", c_.walls(i).name(), cat(idx("walls", i), "shape")});
    for (int i = 0; i < c_.bodies_size(); ++i)
      regions.push_back(
          {&c_.bodies(i).shape(), "body", c_.bodies(i).name(), cat(idx("bodies", i), "shape")});
    const double shell = default_shell_thickness(c_);
    std::vector<std::unique_ptr<Shape>> shapes;
    std::vector<double> needs;
    for (const auto& r : regions) {
      shapes.push_back(compile_shape(*r.shape, d, shell));
      needs.push_back(walk_work(*shapes.back(), spec, around));
    }
    const std::vector<double> share = share_work(needs, kRegionCheckWork);
    for (std::size_t k = 0; k < regions.size(); ++k) {
      const Shape& shape = *shapes[k];
      const Region& r = regions[k];
      const PointCount n = count_lattice_points(shape, spec, around, domain, share[k]);
      const double inside = n.in_core, near = n.points;
      const std::string what = r.kind + (r.name.empty() ? "" : " '" + r.name + "'");
      const std::string points = shape.explicit_points() ? "points" : "lattice points";
      if (n.exact && inside < 1) {
        error(r.field, what + " places no particles: " +
                           (near >= 1 ? "none of its " + count_text(near) + " " + points + " lies"
                                      : std::string("it has no ") + points +
                                            " (dx = " + num(c_.dx()) + ")") +
                           " inside the domain" + domain_text() + "; the shape spans " +
                           box_text(shape.bounds()));
      } else if (r.kind != "wall" && (n.exact || n.hits >= kMinHitsToRefuse) &&
                 inside < kMinRegionFractionInDomain * near) {
        const std::string about = n.exact ? "" : "about ";
        error(r.field, what + " lies mostly outside the domain" + domain_text() + ": " + about +
                           count_text(std::round(inside)) + " of its " + about +
                           count_text(std::round(near)) + " " + points + " are inside" +
                           (n.exact ? "" : " (counted on a sample)") + "; at least " +
                           count_text(100 * kMinRegionFractionInDomain) + "% must be");
      }
    }
  }
  // Points of a region a sample must have found before the region is refused on it.
  static constexpr double kMinHitsToRefuse = 100;
  std::string domain_text() const {
    return " (" + box_text({to_point(c_.domain().lo()), to_point(c_.domain().hi())}) + ")";
  }
  // "x in [0, 2], y in [0, 2]"
  std::string box_text(const Aabb& b) const {
    std::string s;
    for (int a = 0; a < c_.dimension(); ++a)
      s += std::string(a ? ", " : "") + "xyz"[a] + " in [" + num(b.lo[a]) + ", " + num(b.hi[a]) +
           "]";
    return s;
  }

  void size_limit() {
    if (!errors_.empty()) return;  // shapes must be valid to estimate
    regions_in_domain();
    if (!errors_.empty()) return;
    const CaseEstimate e = estimate_case(c_);
    if (estimate_ != nullptr) *estimate_ = e;
    if (e.total() < 1)
      error("fluids", "the case places no particles (check shapes against domain and dx)");
    if (limits_.max_particles > 0 && e.total() > limits_.max_particles)
      error("dx", "case too large: estimated " + count_text(e.total()) + " particles; " +
                      limits_.source + " limit is " + count_text(limits_.max_particles) +
                      " (--max-particles): increase dx or shrink the domain");
    if (limits_.max_memory_bytes > 0 && e.bytes > limits_.max_memory_bytes)
      error("dx", "case too large: estimated " + gib_text(e.bytes) + " GiB of memory for " +
                      count_text(e.total()) + " particles; " + limits_.source + " limit is " +
                      gib_text(limits_.max_memory_bytes) +
                      " GiB (--max-memory-gib): increase dx or shrink the domain");
    if (!errors_.empty()) return;
    for (auto& w : check_wall_thickness(c_)) errors_.push_back(std::move(w));
  }
  static std::string gib_text(double bytes) { return number_text(bytes / 1073741824.0, 3); }

  const v1::Case& c_;
  ValidationLimits limits_;
  CaseEstimate* estimate_;
  std::vector<FieldError> errors_;
  std::set<std::string> names_;
  std::map<std::string, v1::MaterialPhase> phase_;
  std::set<std::string> body_names_;
  std::set<std::string> reported_;
  std::size_t unreported_ = 0;
  bool dim_ok_ = true;
};

}  // namespace

std::vector<FieldError> validate_case(const v1::Case& c, const ValidationLimits& limits,
                                      CaseEstimate* estimate) {
  return Validator(c, limits, estimate).run();
}

std::string join_errors(const std::vector<FieldError>& errors) {
  std::string s;
  for (const auto& e : errors) s += (s.empty() ? "" : "; ") + e.to_string();
  return s;
}

}  // namespace sph
