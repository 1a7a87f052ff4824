#pragma once
// Rigid bodies without a fluid solver around them: the particles a case's scene builder makes
// (bodies, fluid, walls) in a ParticleStore, and the body table initialised from them.
#include <memory>
#include <vector>

#include "case/materials.h"
#include "solver/bodies/rigid_bodies.h"
#include "solver/scene/scene_builder.h"

namespace sph {

// Places the particles of the case's scene in `s` and builds the body table (bodies start
// with velocity u0 and angular velocity w0; rigid particles get their rigid velocities).
template <int D>
inline std::unique_ptr<RigidBodies<D>> bodies_of(const v1::Case& c, ParticleStore<D>& s,
                                                 const Vec<D>& u0 = Vec<D>::Zero(),
                                                 const AngVec<D>& w0 = AngVec<D>::Zero()) {
  const auto mats = resolve_materials(c);
  std::vector<double> rho_s, rho_f;
  for (const auto& b : c.bodies()) {
    rho_s.push_back(mats[static_cast<size_t>(material_index(mats, b.material()))].rho0);
    rho_f.push_back(0);
  }
  auto bodies = std::make_unique<RigidBodies<D>>(s, c, rho_s, rho_f);
  std::vector<SceneParticle> ps;
  SceneBuilder(c, mats).for_each([&](const SceneParticle& p) { ps.push_back(p); });
  s.resize(ps.size(), ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    for (int a = 0; a < D; ++a) s.x[i][a] = ps[i].x[a];
    s.m[i] = ps[i].mass;
    s.kind[i] = ps[i].kind;
    s.material[i] = ps[i].material;
    s.rho[i] = ps[i].rho;
    s.id[i] = static_cast<ParticleId>(i);
    bodies->body_index()[i] = ps[i].body;
  }
  const auto nb = static_cast<std::size_t>(c.bodies_size());
  bodies->initialize(Comm(MPI_COMM_WORLD), c.dx(), std::vector<Vec<D>>(nb, u0),
                     std::vector<AngVec<D>>(nb, w0));
  bodies->update_owned_velocities();
  return bodies;
}

}  // namespace sph
