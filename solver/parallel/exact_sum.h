#pragma once
// Sums over particles and ranks whose result does not depend on the order of the terms:
// every term is converted to a 128-bit fixed-point integer on a scale set by the largest
// term (a first reduction), integers are summed exactly (associative) and the total is
// rounded back once. Quantities that feed back into the dynamics (rigid-body force and
// torque) are summed this way so that results stay bitwise identical for any rank count.
// Resolution: 2^-100 of the largest term, far below double precision of the terms.
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "solver/parallel/comm.h"

namespace sph {

__extension__ typedef __int128 Int128;  // GCC/Clang extension; -Wpedantic would flag plain use

namespace detail {
void sum_int128(std::vector<Int128>& v, const Comm& comm);
}

// for_each(emit) must call emit(slot, value) for every term, the same way on both calls.
template <class ForEach>
std::vector<double> exact_sum(std::size_t slots, ForEach&& for_each, const Comm& comm) {
  // A NaN term makes its slot's scale infinite (std::max would drop it), so that the slot
  // comes out NaN: a non-finite particle force must reach the body as one, for the guards.
  std::vector<double> scale(slots, 0.0);
  for_each([&](std::size_t k, double x) {
    scale[k] = std::max(scale[k], std::isnan(x) ? HUGE_VAL : std::abs(x));
  });
  comm.max_inplace(scale);
  constexpr int kFractionBits = 100;  // terms < 2^100; up to 2^26 terms fit in 127 bits
  std::vector<int> shift(slots, 0);
  for (std::size_t k = 0; k < slots; ++k)
    if (scale[k] > 0 && std::isfinite(scale[k]))
      shift[k] = kFractionBits - std::ilogb(scale[k]) - 1;
  std::vector<Int128> acc(slots, 0);
  for_each([&](std::size_t k, double x) {
    // Converting a non-finite value to an integer is undefined: such slots are not summed.
    if (x != 0.0 && std::isfinite(scale[k])) acc[k] += static_cast<Int128>(std::ldexp(x, shift[k]));
  });
  detail::sum_int128(acc, comm);
  std::vector<double> out(slots);
  for (std::size_t k = 0; k < slots; ++k)
    out[k] = std::isfinite(scale[k]) ? std::ldexp(static_cast<double>(acc[k]), -shift[k])
                                     : std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace sph
