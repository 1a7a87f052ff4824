// The anisotropic resolution of an elastic body (ElasticBody.anisotropy, ASPH: thesis sec. 3.5,
// P-II; docs/asph.md): the ratio, the thickness direction, a thickness of whole layers of dx,
// and what the solver does not yet couple with anisotropic particles.
#include <cmath>
#include <cstdio>

#include "case/anisotropy.h"
#include "case/validate/validator.h"

namespace sph::case_validation {

void Validator::anisotropy(const v1::ElasticBody& b, const std::string& f, bool shape_ok) {
  const std::string g = cat(f, "anisotropy");
  const int d = c_.dimension();
  const double r = b.anisotropy().ratio();
  if (!finite(r) || r < 1 || r > kMaxAnisotropyRatio)
    error(cat(g, "ratio"), "must be in [1, " + num(kMaxAnisotropyRatio) +
                               "] (the spacing along the surface over " +
                               "the spacing dx through the thickness), got " + num(r));
  const v1::Vec3& n = b.anisotropy().thickness_direction();
  const std::string nf = cat(g, "thickness_direction");
  bool axis_ok = false;
  if (!finite(n.x()) || !finite(n.y()) || !finite(n.z()))
    vec(n, nf);
  else if (thickness_axis(b, d) < 0)
    error(nf, std::string("must be a coordinate axis (+-x, +-y") + (d == 3 ? ", +-z" : "") +
                  "): anisotropic bodies are resolved on a lattice aligned with the axes");
  else
    axis_ok = true;
  // Whole layers through the thickness: the lattice puts one particle per dx across it.
  if (axis_ok && shape_ok && d >= 2 && d <= 3 && c_.dx() > 0 && finite(c_.dx())) {
    if (b.shape().has_points()) {
      error(cat(f, "shape.points"), "an anisotropic body needs an interior to fill");
    } else {
      const int axis = thickness_axis(b, d);
      const Aabb box = compile_shape(b.shape(), d, default_shell_thickness(c_))->bounds();
      const double layers = (box.hi[axis] - box.lo[axis]) / c_.dx();
      if (finite(layers) && std::abs(layers - std::round(layers)) > 1e-6 * std::max(1.0, layers)) {
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      "spans %g m along %c, the thickness direction of its anisotropy: not a "
                      "whole number of dx = %g (%.4g layers)",
                      box.hi[axis] - box.lo[axis], "xyz"[axis], c_.dx(), layers);
        error(cat(f, "shape"), buf);
      }
    }
  }
  // Not yet with anisotropic particles (docs/asph.md): the fluid's wall condition and heat
  // conduction take elastic particles as isotropic of volume dx^D, the hourglass control's
  // pair springs use the isotropic kernel.
  if (c_.fluids_size() > 0 || c_.open_boundaries_size() > 0)
    error(g,
          "an anisotropic body cannot be coupled with fluid yet (the case has fluid regions "
          "or open boundaries)");
  if (c_.has_thermal()) error(g, "an anisotropic body does not conduct heat yet (thermal { } set)");
  if (const int k = material_position(b.material()); k >= 0) {
    const auto& m = c_.materials(k);
    if (m.has_hourglass_control() && m.hourglass_control() > 0)
      error(cat(idx("materials", k), "hourglass_control"),
            "is not supported with anisotropic elastic bodies yet (material '" + m.name() +
                "' is used by " + g + ")");
  }
}

}  // namespace sph::case_validation
