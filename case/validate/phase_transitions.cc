// Phase transitions (Fuchs 2021): materials, driver, join radius, latent heat.
#include "case/validate/validator.h"

#include "case/estimate.h"

namespace sph::case_validation {

void Validator::phase_transitions() {
  for (int i = 0; i < c_.phase_transitions_size(); ++i) {
    const auto& pt = c_.phase_transitions(i);
    const std::string f = idx("phase_transitions", i);
    material_ref(pt.solid_material(), v1::SOLID, cat(f, "solid_material"), true);
    material_ref(pt.fluid_material(), v1::FLUID, cat(f, "fluid_material"), true);
    // A transition's materials conduct (diffuse) like any region's, even before a particle
    // of them exists (the melt of a scene that starts solid).
    transport_properties(pt.solid_material(), cat(f, "solid_material"));
    transport_properties(pt.fluid_material(), cat(f, "fluid_material"));
    // A particle keeps its mass when it changes phase (Fuchs 2021 eq. 29; all the paper's
    // examples give both phases one density): with two densities the melt would start
    // compressed or stretched by their ratio, an EOS pressure jump at every transition.
    const int ks = material_position(pt.solid_material()),
              kf = material_position(pt.fluid_material());
    if (ks >= 0 && kf >= 0 && c_.materials(ks).density() != c_.materials(kf).density())
      error(cat(f, "fluid_material"),
            "density " + num(c_.materials(kf).density()) + " of '" + pt.fluid_material() +
                "' differs from the solid's " + num(c_.materials(ks).density()) + " ('" +
                pt.solid_material() +
                "'): a particle keeps its mass when it changes phase, so both materials need "
                "the same density");
    if (pt.driver() == v1::DRIVER_UNSPECIFIED)
      error(cat(f, "driver"), "is required (TEMPERATURE or CONCENTRATION)");
    // A transition needs the field that drives it (issue: only the effects a scene calls for).
    if (pt.driver() == v1::TEMPERATURE && !c_.has_thermal())
      error(cat(f, "driver"),
            "TEMPERATURE needs heat conduction: add a `thermal { }` block to the case");
    if (pt.driver() == v1::CONCENTRATION && !c_.has_diffusion())
      error(cat(f, "driver"),
            "CONCENTRATION needs concentration diffusion: add a `diffusion { }` block");
    if (!finite(pt.transition_value())) error(cat(f, "transition_value"), "must be finite");
    non_negative(pt.hysteresis(), cat(f, "hysteresis"));
    if (pt.has_join_radius()) positive(pt.join_radius(), cat(f, "join_radius"));
    // Particles of a body link when closer than the join radius; at dx or less lattice
    // neighbours do not, and every body a transition touches falls apart into single particles.
    if (pt.has_join_radius() && pt.join_radius() > 0 && pt.join_radius() <= 1.01 * c_.dx())
      error(cat(f, "join_radius"),
            "must be larger than dx (" + num(c_.dx()) +
                "): particles one lattice spacing apart must link, or every body a transition "
                "touches breaks into single particles (default 1.5 dx)");
    if (pt.has_join_radius() && pt.join_radius() >= kernel_support_radius(c_))
      error(cat(f, "join_radius"), "must be smaller than the kernel support radius (" +
                                       num(kernel_support_radius(c_)) + ")");
    // Only solidified particles merge bodies on touching; a transition that never freezes has
    // none. The regrouping measures distances without periodic images, so two bodies touching
    // across a periodic face would be found every step and never merged.
    if (pt.merge_bodies() && !pt.reversible())
      error(cat(f, "merge_bodies"),
            "needs reversible: true (bodies merge where a solidified particle touches another "
            "body; without solidification there is none)");
    if (pt.merge_bodies() && (c_.periodic_x() || c_.periodic_y() || c_.periodic_z()))
      error(cat(f, "merge_bodies"), "is not supported in a periodic domain");
    if (pt.has_max_bodies() && pt.max_bodies() < c_.bodies_size())
      error(cat(f, "max_bodies"), "must be >= the number of bodies in the case (" +
                                      std::to_string(c_.bodies_size()) + ")");
    if (pt.has_latent_heat() || pt.has_latent_heat_interval()) {
      if (pt.driver() == v1::CONCENTRATION)
        error(cat(f, pt.has_latent_heat() ? "latent_heat" : "latent_heat_interval"),
              "latent heat needs driver TEMPERATURE");
      if (!pt.has_latent_heat())
        error(cat(f, "latent_heat"), "is required with latent_heat_interval");
      else
        positive(pt.latent_heat(), cat(f, "latent_heat"));
      // The apparent capacity L/dT needs an interval of finite width (Fuchs 2021 Remark 3).
      if (!pt.has_latent_heat_interval())
        error(cat(f, "latent_heat_interval"),
              "is required with latent_heat (the temperature interval over which it is "
              "absorbed, centred on transition_value)");
      else
        positive(pt.latent_heat_interval(), cat(f, "latent_heat_interval"));
    }
    for (int j = 0; j < i; ++j)
      if (c_.phase_transitions(j).solid_material() == pt.solid_material() ||
          c_.phase_transitions(j).fluid_material() == pt.fluid_material())
        error(f, "a material takes part in two phase transitions (also in phase_transitions[" +
                     std::to_string(j) + "])");
  }
}

}  // namespace sph::case_validation
