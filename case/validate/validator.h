#pragma once
// The case validator behind validate_case (case/validate.h), internal to it. validate_case
// calls the sections in a fixed order, which is the order of the errors; each section is
// defined in the file of its name in this folder and adds its errors through error(), which
// keeps the first kMaxReportedErrors and counts the rest.
#include <cmath>
#include <cstddef>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "case/estimate.h"
#include "case/geometry.h"
#include "case/lattice.h"
#include "case/number_text.h"
#include "case/validate.h"
#include "sph/v1/case.pb.h"

namespace sph::case_validation {

// "fluids[2]"
inline std::string idx(const std::string& base, int i) {
  return base + "[" + std::to_string(i) + "]";
}
// "fluids[2].shape"
inline std::string cat(const std::string& base, const std::string& f) {
  return base.empty() ? f : base + "." + f;
}
inline bool finite(double v) {
  return std::isfinite(v);
}

class Validator {
 public:
  Validator(const v1::Case& c, const ValidationLimits& limits, CaseEstimate* estimate)
      : c_(c), limits_(limits), estimate_(estimate) {}

  // The sections, in the order validate_case calls them.
  bool within_bounds();  // top_level.cc: false if a bound of case_limits.h is broken
  void top_level();      // top_level.cc
  bool dimension_ok() const { return dim_ok_; }
  void materials();                                                    // materials.cc
  void fluid(const v1::FluidRegion& r, const std::string& f);          // fluids.cc
  void wall(const v1::Wall& w, const std::string& f);                  // walls.cc
  void body(const v1::RigidBody& b, const std::string& f);             // bodies.cc
  void contact();                                                      // bodies.cc
  void elastic_body(const v1::ElasticBody& b, const std::string& f);   // elastic_bodies.cc
  void periodic_seam(const v1::ElasticBody& b, const std::string& f);  // elastic_bodies.cc
  void phase_transitions();                                            // phase_transitions.cc
  void thermal();                                                      // thermal.cc
  void open_boundaries();                                              // open_boundaries.cc
  void run_settings();                                                 // run_settings.cc
  void density_diffusion();                                            // density_diffusion.cc
  void particle_shifting();                                            // particle_shifting.cc
  void riemann_dissipation();                                          // riemann_dissipation.cc
  void probes();                                                       // probes.cc
  void case_size();                                                    // case_size.cc

  // Errors of a check outside this class (validate_reference, ...): through error(), or all
  // of them appended as they are.
  void add(const std::vector<FieldError>& errors);
  void add_uncapped(std::vector<FieldError> errors);

  // The errors, with a last line counting those beyond kMaxReportedErrors.
  std::vector<FieldError> reported();

 private:
  // field_checks.cc
  void error(const std::string& field, const std::string& msg);
  void positive(double v, const std::string& field, const std::string& what = "must be > 0");
  void non_negative(double v, const std::string& field);
  void vec(const v1::Vec3& v, const std::string& field);
  void extent(double v, const std::string& field);
  bool point_ok(const v1::Vec3& v) const;
  void point(const v1::Vec3& v, const std::string& field);
  static std::string num(double v) { return number_text(v); }

  // shapes.cc, motion.cc
  void shape(const v1::Shape& s, const std::string& f, bool top);
  void mesh(const v1::TriangleMesh& m, const std::string& f);
  void distance_grid(const v1::DistanceGrid& g, const std::string& f);
  void time_function(const v1::TimeFunction& tf, const std::string& f);
  void motion(const v1::Motion& m, const std::string& f);
  void growth_speed(const v1::Wall& w, const std::string& f, bool shape_ok);  // walls.cc
  // velocity_fields.cc: beam_mode is refused unless elastic_body.
  void velocity_field(const v1::VelocityField& v, const std::string& f, bool elastic_body);

  // materials.cc, thermal.cc
  static constexpr int kMaterialsListed = 8;
  void material_ref(const std::string& name, v1::MaterialPhase want, const std::string& field,
                    bool required);
  int material_position(const std::string& name) const;
  void elastic_constants(const v1::Material& m, const std::string& f);
  void plasticity(const v1::Material& m, const std::string& f);
  void porous(const v1::Material& m, const std::string& f);  // porous.cc
  // porous.cc, from elastic_body: initial_concentration and concentration_holds.
  void concentration_holds(const v1::ElasticBody& b, const std::string& f, bool shape_ok);
  // porous.cc, from run_settings: the load step against the explicit diffusion bounds.
  void quasi_static_diffusion();
  // elastic_bodies.cc: ElasticBody.body_force_field.manufactured_torsion.
  void manufactured_torsion(const v1::ElasticBody& b, const std::string& f);
  void transport_properties(const std::string& name, const std::string& field);

  // anisotropy.cc, from elastic_body: ElasticBody.anisotropy; shape_ok: the body's shape passed
  // its checks (it may be compiled).
  void anisotropy(const v1::ElasticBody& b, const std::string& f, bool shape_ok);

  // case_size.cc
  void regions_in_domain();
  // elastic_bodies.cc: whether each constraint region of an elastic body holds particles of
  // it, a walk over the body's points in the region that shares kRegionCheckWork with the
  // regions' walks.
  struct ConstraintCheck {
    std::shared_ptr<const Shape> body;
    std::unique_ptr<Shape> region;
    // Walls, rigid bodies and earlier elastic bodies, which take lattice points first.
    std::shared_ptr<const std::vector<std::shared_ptr<const Shape>>> claims;
    std::unique_ptr<Shape> part;  // the body's points in the region, claims taken out
    std::string field, what;
    double need = 0;   // work to test every point
    LatticeSpec spec;  // the body's lattice (stretched for an anisotropic body)
  };
  std::vector<ConstraintCheck> constraint_checks(const LatticeSpec& spec, const Aabb& domain) const;
  void check_constraint(const ConstraintCheck& k, const LatticeSpec& spec, const Aabb& domain,
                        double budget);
  // Points of a region a sample must have found before the region is refused on it.
  static constexpr double kMinHitsToRefuse = 100;
  std::string domain_text() const;
  std::string box_text(const Aabb& b) const;
  static std::string gib_text(double bytes) { return number_text(bytes / 1073741824.0, 3); }

  const v1::Case& c_;
  ValidationLimits limits_;
  CaseEstimate* estimate_;
  std::vector<FieldError> errors_;
  std::set<std::string> names_;                     // material names
  std::map<std::string, v1::MaterialPhase> phase_;  // of each material name
  std::set<std::string> body_names_;
  std::set<std::string> elastic_names_;
  std::set<std::string> reported_;  // materials whose missing coefficients are reported
  std::size_t unreported_ = 0;
  bool dim_ok_ = true;
};

}  // namespace sph::case_validation
