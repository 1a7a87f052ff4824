#include "case/anisotropy.h"

#include <algorithm>
#include <cmath>

#include "case/estimate.h"
#include "case/geometry.h"

namespace sph {

bool is_anisotropic(const v1::ElasticBody& b) {
  return b.has_anisotropy();
}

int thickness_axis(const v1::ElasticBody& b, int dim) {
  const v1::Vec3& n = b.anisotropy().thickness_direction();
  if (dim == 2 && n.z() != 0) return -1;
  const double v[3] = {n.x(), n.y(), dim == 3 ? n.z() : 0.0};
  if (v[0] == 0 && v[1] == 0 && v[2] == 0) return dim == 3 ? 2 : 1;  // the default
  int axis = -1;
  for (int a = 0; a < dim; ++a) {
    if (v[a] == 0) continue;
    if (axis >= 0) return -1;  // two components: not an axis
    axis = a;
  }
  return axis;
}

LatticeSpec elastic_lattice_spec(const v1::Case& c, const v1::ElasticBody& b) {
  LatticeSpec spec{c.dimension(), c.dx(), to_point(c.lattice_origin())};
  if (!is_anisotropic(b)) return spec;
  const int axis = thickness_axis(b, c.dimension());
  const double r = b.anisotropy().ratio();
  // Out of range (validation names it): the case's lattice, so that no walk over a shape is
  // stretched by zero, a negative or a huge ratio.
  if (!(r >= 1 && r <= kMaxAnisotropyRatio)) return spec;
  for (int a = 0; a < c.dimension(); ++a)
    if (a != axis) spec.stretch[a] = r;
  return spec;
}

double elastic_particle_volume(const v1::Case& c, const v1::ElasticBody& b) {
  const int d = c.dimension();
  const double vol = std::pow(c.dx(), d);
  const LatticeSpec spec = elastic_lattice_spec(c, b);
  return vol * spec.stretch.x() * spec.stretch.y() * (d == 3 ? spec.stretch.z() : 1.0);
}

double search_radius(const v1::Case& c) {
  double rc = kernel_support_radius(c);
  for (const auto& b : c.elastic_bodies())
    if (is_anisotropic(b)) {
      const LatticeSpec spec = elastic_lattice_spec(c, b);
      rc = std::max(rc, spec.stretch.maxCoeff() * kernel_support_radius(c));
    }
  return rc;
}

}  // namespace sph
