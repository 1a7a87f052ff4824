#pragma once
// Builds the particles of a case: walls, then rigid bodies, then fluids, then the buffers of
// open boundaries, each on the lattice of spacing dx inside its shape (or at explicit points),
// clipped to the domain. A lattice point claimed by a wall is not used by a body, a fluid or a
// buffer, one claimed by a body not by a fluid or a buffer, one inside a buffer's region not
// by a fluid, and one claimed by an earlier region of the same kind not by a later one. The order
// of generation is fixed, so global ids are the same on every rank and in every run.
#include <functional>
#include <memory>
#include <vector>

#include "case/geometry.h"
#include "case/materials.h"
#include "solver/core/types.h"
#include "sph/v1/case.pb.h"

namespace sph {

struct SceneParticle {
  Kind kind = Kind::kFluid;
  std::uint16_t material = kNoMaterial;
  std::uint16_t wall = 0;        // index of the wall (walls only)
  std::int32_t body = -1;        // index of the rigid body (rigid particles only)
  std::int32_t region = -1;      // index of the fluid region (fluid particles only)
  std::int32_t open = -1;        // index of the open boundary (buffer particles only)
  std::int32_t elastic = -1;     // index of the elastic body (elastic particles only)
  std::int32_t constraint = -1;  // index of that body's constraint holding it, or -1 (free)
  Point3 x = Point3::Zero();
  Point3 v = Point3::Zero();
  double rho = 1, mass = 1;
};

class SceneBuilder {
 public:
  SceneBuilder(const v1::Case& c, const std::vector<MaterialParams>& materials);
  // Calls fn for every particle of the scene, in the fixed global order.
  void for_each(const std::function<void(const SceneParticle&)>& fn) const;
  // Reference density given to dummy wall particles (the first fluid's).
  double wall_density() const { return wall_rho_; }

 private:
  const v1::Case& c_;
  const std::vector<MaterialParams>& mats_;
  std::vector<std::unique_ptr<Shape>> walls_, bodies_, fluids_, opens_, elastic_;
  std::vector<std::vector<std::unique_ptr<Shape>>> constraints_;  // per elastic body
  double wall_rho_ = 1;
};

}  // namespace sph
