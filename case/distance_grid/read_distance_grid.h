#pragma once
// Reads the signed-distance grid of a DistanceGrid shape from an HDF5 file into the message.
#include <cstddef>
#include <string>

#include "sph/v1/case.pb.h"

namespace sph {

// Reads dataset `out.dataset()` (default "sdf") of the HDF5 file at `path` into `out.counts`
// and `out.values` (x fastest). The dataset must have `dim` axes, each of at least 2 nodes, a
// numeric type and at most `max_nodes` nodes; a larger one is refused before it is read.
// Throws std::runtime_error naming the file and what is wrong with it.
void read_distance_grid(const std::string& path, int dim, std::size_t max_nodes,
                        v1::DistanceGrid& out);

}  // namespace sph
