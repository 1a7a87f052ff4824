// Open boundaries: inflow and outflow buffer zones.
#include "case/validate/validator.h"

#include <cmath>
#include <set>
#include <utility>

#include "case/estimate.h"

namespace sph::case_validation {

// Buffer zones (solver/boundaries/open_boundaries.h): a box in the domain, one layer of
// whole particle rows at least r_c thick along a non-periodic coordinate axis.
void Validator::open_boundaries() {
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
    if (o.has_backflow_stabilization()) {
      if (velocity)
        error(cat(f, "backflow_stabilization"),
              "only used by a pressure outlet (an OUTFLOW without mean_velocity)");
      else if (!(o.backflow_stabilization() >= 0 && o.backflow_stabilization() <= 1))
        error(cat(f, "backflow_stabilization"),
              "must be in [0, 1] (got " + num(o.backflow_stabilization()) + ")");
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

}  // namespace sph::case_validation
