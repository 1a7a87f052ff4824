#pragma once
// Probes: pressure, density and velocity at fixed points, interpolated from fluid particles
// with the Shepard-normalised kernel sum (Fuchs 2021 eq. 13). The rank owning the point's
// cell evaluates it; a sum over ranks gives every rank the values.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "solver/core/neighbor_list.h"
#include "solver/parallel/comm.h"

namespace sph {

template <int D>
struct ProbeSet {
  std::string name;
  std::vector<Vec<D>> points;
};

template <int D, class K>
class Probes {
 public:
  static constexpr const char* kName = "probes";
  static constexpr int kValues = 2 + D;  // pressure, density, velocity
  Probes(std::vector<ProbeSet<D>> sets, const K& kernel) : sets_(std::move(sets)), k_(kernel) {}
  const std::vector<ProbeSet<D>>& sets() const { return sets_; }

  // values[set][point * kValues + q], identical on every rank; NaN where no fluid is near.
  std::vector<std::vector<double>> sample(const ParticleStore<D>& s, const NeighborList<D>& nl,
                                          const CellGrid<D>& grid, const CellBox<D>& mine,
                                          const Comm& comm) const {
    std::vector<double> flat;
    for (const auto& set : sets_) {
      for (const Vec<D>& xp : set.points) {
        double acc[kValues + 1] = {};
        const ICoord<D> c = grid.coord(xp);
        bool inside = true;
        for (int a = 0; a < D; ++a) inside = inside && c[a] >= 0 && c[a] < grid.n[a];
        if (inside && mine.contains(c)) {
          nl.for_each_near(c, [&](std::uint32_t j) {
            if (s.kind[j] != Kind::kFluid) return;
            const double w = k_.W((xp - s.x[j]).norm());
            if (w == 0.0) return;
            const double vw = s.m[j] / s.rho[j] * w;
            acc[0] += vw * s.p[j];
            acc[1] += vw * s.rho[j];
            for (int a = 0; a < D; ++a) acc[2 + a] += vw * s.v[j][a];
            acc[kValues] += vw;
          });
        }
        flat.insert(flat.end(), acc, acc + kValues + 1);
      }
    }
    comm.sum_inplace(flat);
    std::vector<std::vector<double>> out;
    std::size_t k = 0;
    for (const auto& set : sets_) {
      std::vector<double> vals;
      for (std::size_t p = 0; p < set.points.size(); ++p, k += kValues + 1) {
        const double wsum = flat[k + kValues];
        for (int q = 0; q < kValues; ++q)
          vals.push_back(wsum > 0 ? flat[k + static_cast<size_t>(q)] / wsum
                                  : std::numeric_limits<double>::quiet_NaN());
      }
      out.push_back(std::move(vals));
    }
    return out;
  }

 private:
  std::vector<ProbeSet<D>> sets_;
  const K& k_;
};

}  // namespace sph
