// Porous elastic solids (thesis sec. 2.3, P-III sec. 2.2; docs/porous_media.md): the pore
// pressure law of a material, the saturation an elastic body starts with and the parts held
// wet, and under quasi-static loading the load step against the explicit diffusion bound.
#include <cstdio>

#include "case/estimate.h"
#include "case/geometry.h"
#include "case/validate/validator.h"

namespace sph::case_validation {

// P-III eq. 2.21: p = C (c - c0), with c a saturation (a volume fraction of the pores' fluid).
void Validator::porous(const v1::Material& m, const std::string& mf) {
  const v1::PorousSolid& p = m.porous();
  const std::string f = cat(mf, "porous");
  non_negative(p.swelling_modulus(), cat(f, "swelling_modulus"));
  if (!(p.reference_saturation() >= 0 && p.reference_saturation() <= 1))
    error(cat(f, "reference_saturation"),
          "must be in [0, 1] (a volume fraction; got " + num(p.reference_saturation()) + ")");
  if (!c_.has_diffusion())
    error(f,
          "needs concentration diffusion (a `diffusion { }` block): the pore fluid's "
          "saturation is the case's concentration");
  bool used = false;
  for (const auto& b : c_.elastic_bodies()) used = used || b.material() == m.name();
  if (!used)
    error(f, "set on material '" + m.name() +
                 "', which no elastic body uses: only an elastic body's stress takes the pore "
                 "pressure");
}

void Validator::concentration_holds(const v1::ElasticBody& b, const std::string& f, bool shape_ok) {
  const std::string why =
      "set, but concentration diffusion is not enabled (add a `diffusion { }` "
      "block)";
  // (Non-finite numbers anywhere in the case are refused before these checks.)
  if (b.has_initial_concentration() && !c_.has_diffusion())
    error(cat(f, "initial_concentration"), why);
  if (b.concentration_holds_size() > 0 && !c_.has_diffusion()) {
    error(cat(f, "concentration_holds"), why);
    return;
  }
  // The porous diffusion sums over isotropic reference neighbours (solver/elastic/
  // porous_diffusion.h); P-II's anisotropic Laplacian (digest sec. 5.3, eqs. 34-39) is not here.
  if (const int k = material_position(b.material());
      k >= 0 && c_.materials(k).has_porous() && b.has_anisotropy())
    error(cat(f, "anisotropy"),
          "a body of a porous material (materials[" + std::to_string(k) +
              "].porous) must be resolved isotropically: its diffusion has no anisotropic form");
  const double end = c_.time().end_time();
  for (int j = 0; j < b.concentration_holds_size(); ++j) {
    const auto& h = b.concentration_holds(j);
    const std::string g = idx(cat(f, "concentration_holds"), j);
    if (!(h.start_time() >= 0))
      error(cat(g, "start_time"), "must be >= 0 [s] (got " + num(h.start_time()) + ")");
    if (h.end_time() < 0 || (h.end_time() > 0 && !(h.end_time() > h.start_time())))
      error(cat(g, "end_time"), "must be > start_time (" + num(h.start_time()) +
                                    " s), or unset for the whole run (got " + num(h.end_time()) +
                                    ")");
    else if (end > 0 && h.start_time() >= end)
      error(cat(g, "start_time"),
            "is at or after time.end_time (" + num(end) + " s): the hold never acts");
    if (!h.has_region()) {
      error(cat(g, "region"), "is required");
      continue;
    }
    if (h.region().has_points()) {
      error(cat(g, "region.points"),
            "a hold region needs an interior (box, ball, ...); a point set holds no particle of "
            "the body");
      continue;
    }
    const std::size_t before = errors_.size();
    shape(h.region(), cat(g, "region"), true);
    if (!shape_ok || errors_.size() != before) continue;
    // A region apart from the body holds nothing: most likely a unit or axis slip.
    const int d = c_.dimension();
    const double shell = default_shell_thickness(c_);
    const Aabb overlap = compile_shape(b.shape(), d, shell)
                             ->bounds()
                             .intersected(compile_shape(h.region(), d, shell)->bounds());
    bool apart = false;
    for (int a = 0; a < d; ++a) apart = apart || overlap.hi[a] < overlap.lo[a];
    if (apart) error(cat(g, "region"), "does not overlap the body's shape: it holds no particle");
  }
}

// The diffusion takes one explicit step per load step, so the load step is bounded by its
// eq. (41) bound, 0.1 rho c_p h^2 / kappa (0.1 rho h^2 / D for a concentration), times the CFL
// factor, as ScalarTransport computes it (solver/physics/scalar_transport.h).
void Validator::quasi_static_diffusion() {
  const double load_step = c_.time().quasi_static().load_step();
  if (!(load_step > 0)) return;
  const double h = smoothing_length(c_);
  const double f = c_.time().has_cfl_factor() ? c_.time().cfl_factor() : 1.0;
  for (int k = 0; k < c_.materials_size(); ++k) {
    const auto& m = c_.materials(k);
    const auto check = [&](bool on, double coefficient, double capacity, const char* what) {
      if (!on || !(coefficient > 0) || !(m.density() > 0) || !(capacity > 0)) return;
      const double bound = f * 0.1 * m.density() * capacity * h * h / coefficient;
      if (load_step <= bound) return;
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "must be at most %.6g s: the explicit %s step of material '%s' (0.1 rho c h^2 "
                    "/ k, Fuchs 2021 eq. 41, times time.cfl_factor), which runs once per load "
                    "step (got %.6g s)",
                    bound, what, m.name().c_str(), load_step);
      error("time.quasi_static.load_step", buf);
    };
    check(c_.has_thermal(), m.thermal_conductivity(), m.heat_capacity(), "heat conduction");
    check(c_.has_diffusion(), m.diffusivity(), 1.0, "diffusion");
  }
}

}  // namespace sph::case_validation
