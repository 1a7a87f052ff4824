#pragma once
// Basic types of the solver. Dimension is a template parameter; vectors are fixed-size Eigen
// types without alignment requirements so they can live in plain std::vector columns and be
// copied bytewise into MPI buffers.
#include <Eigen/Core>
#include <cstdint>

namespace sph {

template <int D>
using Vec = Eigen::Matrix<double, D, 1, Eigen::DontAlign>;
template <int D>
using Mat = Eigen::Matrix<double, D, D, Eigen::DontAlign>;

// What a particle is. Walls are dummy particles of fixed or prescribed motion (Adami 2012);
// rigid particles belong to a rigid body (Fuchs 2021); elastic particles belong to a
// deformable body of total Lagrangian SPH (solver/elastic/), which the fluid sees as a
// moving wall (Zhang, Rezavand, Hu 2021).
enum class Kind : std::uint8_t { kFluid = 0, kWall = 1, kRigid = 2, kElastic = 3 };

using ParticleId = std::int64_t;

// Material index for dummy particles that have no material of their own.
inline constexpr std::uint16_t kNoMaterial = 0xFFFF;

}  // namespace sph
