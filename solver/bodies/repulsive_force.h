#pragma once
// The short-range repulsive force of Glowinski, Pan, Hesla, Joseph 1999 (IJMF 25:755), as
// Reder et al. 2021 eq. (24) give it: F = c ((delta - d)/delta)^2 for a gap d < delta between
// two surfaces, 0 beyond. It keeps bodies apart before they touch, in the lubrication range
// the fluid cannot resolve, instead of a contact law. Here it acts between the particles of
// different bodies (and walls), d the gap between particle surfaces |x_r - x_r'| - dx; past
// contact (d < 0) it keeps growing with the same parabola.

namespace sph {

struct RepulsiveForce {
  double strength = 0;  // c [N], the force at zero gap
  double range = 0;     // delta [m]
  RepulsiveForce(double c, double delta) : strength(c), range(delta) {}

  // Magnitude pushing the pair apart at gap d (Reder et al. 2021 eq. 24).
  double force(double d) const {
    if (d >= range) return 0.0;
    const double s = (range - d) / range;
    return strength * s * s;
  }
  // The slope |dF/dd| at an overlap of one range (d = -delta), 4 c / delta: the stiffness
  // that bounds the contact sub-step (Fuchs 2021 eq. 41 with k_c replaced by it).
  double stiffness() const { return range > 0 ? 4 * strength / range : 0.0; }
};

}  // namespace sph
