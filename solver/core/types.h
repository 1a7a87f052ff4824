#pragma once
// Basic types of the solver. Dimension is a template parameter; vectors are fixed-size Eigen
// types without alignment requirements so they can live in plain std::vector columns and be
// copied bytewise into MPI buffers.
#include <Eigen/Core>
#include <cstdint>

namespace sph {

template <int D>
using Vec = Eigen::Matrix<double, D, 1, Eigen::DontAlign>;

// What a particle is. Walls are dummy particles of fixed or prescribed motion (Adami 2012);
// rigid particles belong to a rigid body (Fuchs 2021).
enum class Kind : std::uint8_t { kFluid = 0, kWall = 1, kRigid = 2 };

using ParticleId = std::int64_t;

// Material index for dummy particles that have no material of their own.
inline constexpr std::uint16_t kNoMaterial = 0xFFFF;

}  // namespace sph
