// Elastic bodies (total Lagrangian SPH, thesis sec. 3): name, shape, elastic material,
// constraints, initial velocity, observation points. Where each lies against the domain and
// whether each constraint holds particles of its body is counted with the other regions
// (case_size.cc).
#include "case/validate/validator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "case/anisotropy.h"
#include "case/estimate.h"
#include "case/lattice.h"

namespace sph::case_validation {

namespace {

bool names_a_series(const std::string& name) {
  return name.find_first_not_of(
             "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
             "0123456789_-") == std::string::npos;
}

// The lattice points of a body inside a region, less those that the regions claiming points
// before the body take (walls, rigid bodies, earlier elastic bodies: the scene builder's order).
class BodyInRegion final : public Shape {
 public:
  BodyInRegion(const Shape& body, const Shape& region,
               const std::vector<std::shared_ptr<const Shape>>& claims)
      : body_(body), region_(region), claims_(claims) {}
  double distance(const Point3& p) const override {
    const double d = std::max(body_.distance(p), region_.distance(p));
    if (d >= 0) return d;
    for (const auto& s : claims_)
      if (s->contains(p)) return 1.0;
    return d;
  }
  Aabb bounds() const override { return body_.bounds().intersected(region_.bounds()); }
  double cost() const override {
    double c = body_.cost() + region_.cost();
    for (const auto& s : claims_) c += s->cost();
    return c;
  }

 private:
  const Shape& body_;
  const Shape& region_;
  const std::vector<std::shared_ptr<const Shape>>& claims_;
};

}  // namespace

void Validator::elastic_body(const v1::ElasticBody& b, const std::string& f) {
  // The name: one namespace with walls and rigid bodies (contact and output name a body by
  // it), and a path of the series elastic/<name>/displacement.
  if (b.name().empty()) {
    if (b.observation_points_size() > 0)
      error(cat(f, "name"),
            "is required with observation_points (they write the series "
            "elastic/<name>/displacement)");
  } else if (!names_a_series(b.name())) {
    error(cat(f, "name"), "may contain only letters, digits, '_' and '-' (it names a series)");
  } else if (body_names_.count(b.name()) > 0) {
    error(cat(f, "name"), "'" + b.name() + "' is already the name of a rigid body");
  } else if (!elastic_names_.insert(b.name()).second) {
    error(cat(f, "name"), "duplicate elastic body name '" + b.name() + "'");
  } else {
    for (int i = 0; i < c_.walls_size(); ++i)
      if (c_.walls(i).name() == b.name()) {
        error(cat(f, "name"), "'" + b.name() + "' is already the name of " + idx("walls", i));
        break;
      }
  }

  bool shape_ok = false;
  if (!b.has_shape()) {
    error(cat(f, "shape"), "is required");
  } else {
    const std::size_t before = errors_.size();
    shape(b.shape(), cat(f, "shape"), true);
    shape_ok = errors_.size() == before;
    if (shape_ok && c_.has_domain()) periodic_seam(b, f);
  }

  // A SOLID material with both elastic constants (their ranges are checked with the
  // material); each missing one is named once, at the material.
  material_ref(b.material(), v1::SOLID, cat(f, "material"), true);
  if (const int k = material_position(b.material());
      k >= 0 && c_.materials(k).phase() == v1::SOLID) {
    const auto& m = c_.materials(k);
    const std::string mf = idx("materials", k);
    const std::string why = "required: material '" + m.name() + "' is used by " +
                            cat(f, "material") + ", an elastic body";
    if (!m.has_youngs_modulus() && reported_.insert(mf + "E").second)
      error(cat(mf, "youngs_modulus"), why);
    if (!m.has_poisson_ratio() && reported_.insert(mf + "nu").second)
      error(cat(mf, "poisson_ratio"), why);
  }

  for (int j = 0; j < b.constraints_size(); ++j) {
    const auto& k = b.constraints(j);
    const std::string g = idx(cat(f, "constraints"), j);
    if (!k.has_region())
      error(cat(g, "region"), "is required");
    else if (k.region().has_points())
      error(cat(g, "region.points"),
            "a constraint region needs an interior (box, ball, ...); a point set holds no "
            "particle of the body");
    else
      shape(k.region(), cat(g, "region"), true);
    if (k.has_motion()) motion(k.motion(), cat(g, "motion"));
  }
  // Issue #36: a body that nothing holds and no fluid loads only falls or drifts.
  if (b.constraints_size() == 0 && c_.fluids_size() == 0)
    error(cat(f, "constraints"),
          "an elastic body needs a constraint or a fluid: this body has no constraint and "
          "the case no fluid region");

  if (b.has_anisotropy()) anisotropy(b, f, shape_ok);

  vec(b.initial_velocity(), cat(f, "initial_velocity"));
  velocity_field(b.initial_velocity_field(), cat(f, "initial_velocity_field"), true);
  if (b.ignore_gravity() && !c_.has_gravity())
    error(cat(f, "ignore_gravity"), "set, but the case has no gravity");

  // Any finite temperature, as for fluids and rigid bodies (the scale is the user's).
  if (b.has_initial_temperature() && !c_.has_thermal())
    error(cat(f, "initial_temperature"),
          "set, but heat conduction is not enabled (add a `thermal { }` block)");
  transport_properties(b.material(), f + ".material");
  concentration_holds(b, f, shape_ok);
  if (b.body_force_field().has_manufactured_torsion()) manufactured_torsion(b, f);

  // Observation points: inside the domain, where the body's particles can be.
  if (c_.has_domain()) {
    Aabb domain{to_point(c_.domain().lo()), to_point(c_.domain().hi())};
    for (int i = 0; i < b.observation_points_size(); ++i) {
      const auto& p = b.observation_points(i);
      const std::string g = idx(cat(f, "observation_points"), i);
      if (!point_ok(p))
        point(p, g);
      else if (!inside_box(to_point(p), domain, c_.dimension()))
        error(g, "lies outside the domain" + domain_text());
    }
  }
}

// The manufactured torsion's force (solver/elastic/manufactured_torsion.h) is the equilibrium
// of a neo-Hookean ring in plane strain.
void Validator::manufactured_torsion(const v1::ElasticBody& b, const std::string& f) {
  const v1::ManufacturedTorsion& t = b.body_force_field().manufactured_torsion();
  const std::string g = cat(f, "body_force_field.manufactured_torsion");
  if (c_.dimension() != 2) error(g, "is a 2D field (a ring in the plane); the case is 3D");
  if (const int k = material_position(b.material());
      k >= 0 && c_.materials(k).elastic_law() != v1::NEO_HOOKEAN)
    error(g, "holds a neo-Hookean ring in shape: material '" + b.material() +
                 "' must have elastic_law NEO_HOOKEAN");
  point(t.center(), cat(g, "center"));
  positive(t.inner_radius(), cat(g, "inner_radius"), "must be > 0 [m]");
  if (!(t.outer_radius() > t.inner_radius()))
    error(cat(g, "outer_radius"),
          "must be > inner_radius (" + num(t.inner_radius()) + "); got " + num(t.outer_radius()));
  if (!(t.angle() > 0 && t.angle() <= std::acos(-1.0) / 2))
    error(cat(g, "angle"), "must be in (0, pi/2] [rad]; got " + num(t.angle()));
  positive(t.ramp_time(), cat(g, "ramp_time"), "must be > 0 [s]");
}

// A ghost image across a periodic seam carries the reference position of the other side, so
// a body within r_c of a periodic face would pair its particles with reference distances a
// period off. Refused until the reference positions are wrapped too.
void Validator::periodic_seam(const v1::ElasticBody& b, const std::string& f) {
  const bool periodic[3] = {c_.periodic_x(), c_.periodic_y(), c_.periodic_z()};
  const Aabb box = compile_shape(b.shape(), c_.dimension(), default_shell_thickness(c_))->bounds();
  const Point3 lo = to_point(c_.domain().lo()), hi = to_point(c_.domain().hi());
  const double rc = kernel_support_radius(c_);
  for (int a = 0; a < c_.dimension(); ++a)
    if (periodic[a] && (box.lo[a] < lo[a] + rc || box.hi[a] > hi[a] - rc)) {
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "comes within the kernel support r_c = %g of the periodic faces along %c "
                    "(the body spans [%g, %g], the domain [%g, %g]): elastic bodies across a "
                    "periodic seam are not supported",
                    rc, "xyz"[a], box.lo[a], box.hi[a], lo[a], hi[a]);
      error(cat(f, "shape"), buf);
      return;
    }
}

std::vector<Validator::ConstraintCheck> Validator::constraint_checks(const LatticeSpec& spec,
                                                                     const Aabb& domain) const {
  const int d = c_.dimension();
  const double shell = default_shell_thickness(c_);
  using Shapes = std::vector<std::shared_ptr<const Shape>>;
  Shapes claims;
  for (const auto& w : c_.walls()) claims.push_back(compile_shape(w.shape(), d, shell));
  for (const auto& r : c_.bodies()) claims.push_back(compile_shape(r.shape(), d, shell));
  std::vector<ConstraintCheck> out;
  for (int i = 0; i < c_.elastic_bodies_size(); ++i) {
    const auto& b = c_.elastic_bodies(i);
    std::shared_ptr<const Shape> body = compile_shape(b.shape(), d, shell);
    if (b.constraints_size() > 0) {
      const auto before = std::make_shared<const Shapes>(claims);
      const std::string what = "elastic body" + (b.name().empty() ? "" : " '" + b.name() + "'");
      for (int j = 0; j < b.constraints_size(); ++j) {
        ConstraintCheck k;
        k.body = body;
        k.region = compile_shape(b.constraints(j).region(), d, shell);
        k.claims = before;
        k.part = std::make_unique<BodyInRegion>(*k.body, *k.region, *k.claims);
        k.field = cat(idx(cat(idx("elastic_bodies", i), "constraints"), j), "region");
        k.what = what;
        k.spec = b.has_anisotropy() ? elastic_lattice_spec(c_, b) : spec;
        const auto* points = body->explicit_points();
        k.need = points ? static_cast<double>(points->size()) * (k.part->cost() + kLatticePointWork)
                        : walk_work(*k.part, k.spec, domain);
        out.push_back(std::move(k));
      }
    }
    claims.push_back(std::move(body));
  }
  return out;
}

// Refused only when every point was tested: a sample can miss a thin clamp.
void Validator::check_constraint(const ConstraintCheck& k, const LatticeSpec& spec,
                                 const Aabb& domain, double budget) {
  bool exact = true, holds = false;
  const auto* points = k.body->explicit_points();
  if (points == nullptr) {
    const PointCount n = count_lattice_points(*k.part, k.spec, domain, domain, budget);
    exact = n.exact;
    holds = n.points >= 1;
  } else {
    // A point set's points stand for themselves (a point set has no interior to walk): the
    // region and the claims are tested at each, as far as the budget goes.
    const double each = k.part->cost() + kLatticePointWork;
    double work = 0;
    for (const auto& p : *points) {
      if (work + each > budget) {
        exact = false;
        break;
      }
      work += each;
      if (inside_box(p, domain, spec.dim) && k.region->contains(p) &&
          std::none_of(k.claims->begin(), k.claims->end(),
                       [&](const auto& s) { return s->contains(p); })) {
        holds = true;
        break;
      }
    }
    charge_lattice_work(work);
  }
  if (exact && !holds)
    error(k.field, "holds no particle of the body: no " +
                       std::string(points ? "point" : "lattice point") + " of " + k.what +
                       " inside the domain" +
                       (k.claims->empty() ? "" : " and outside the walls and bodies before it") +
                       " lies in the region (the body spans " + box_text(k.body->bounds()) +
                       ", the region " + box_text(k.region->bounds()) + ")");
}

}  // namespace sph::case_validation
