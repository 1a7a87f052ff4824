#include "case/validate_surface_tension.h"

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "case/case_limits.h"
#include "case/number_text.h"

namespace sph {
namespace {

std::string field(const char* list, int i, const char* name) {
  return std::string("surface_tension.") + list + "[" + std::to_string(i) + "]." + name;
}

// The contact angles validated at a free surface [degrees].
constexpr double kMinFreeSurfaceAngle = 60, kMaxFreeSurfaceAngle = 105;

class SurfaceTensionValidator {
 public:
  explicit SurfaceTensionValidator(const v1::Case& c) : c_(c) {
    for (const auto& m : c.materials()) phase_.emplace(m.name(), m.phase());
    for (const auto& w : c.walls()) walls_.insert(w.name());
  }

  std::vector<FieldError> run() {
    const auto& st = c_.surface_tension();
    if (st.pairs_size() == 0) {
      error("surface_tension.pairs", "give at least one pair (material_a, material_b, sigma)");
      return std::move(errors_);
    }
    // Each unordered pair of materials at most once, so a pair list
    // longer than that is wrong whatever it holds; refused before it is looked at.
    constexpr int kMaxPairs = kMaxMaterials * (kMaxMaterials + 1) / 2;
    if (st.pairs_size() > kMaxPairs) {
      error("surface_tension.pairs", "has " + std::to_string(st.pairs_size()) + " pairs; at most " +
                                         std::to_string(kMaxPairs) +
                                         " (one per pair of materials) are allowed");
      return std::move(errors_);
    }
    std::map<std::pair<std::string, std::string>, int> seen;
    for (int i = 0; i < st.pairs_size(); ++i) {
      const auto& p = st.pairs(i);
      const bool a_ok = fluid_material(p.material_a(), field("pairs", i, "material_a"), true);
      if (!std::isfinite(p.sigma()) || !(p.sigma() > 0))
        error(field("pairs", i, "sigma"), "must be > 0 and finite [N/m]; got " + num(p.sigma()));
      if (p.material_b().empty()) {
        // A free surface: material_a against void.
        if (a_ok) free_surface(p, i);
        continue;
      }
      const bool b_ok = fluid_material(p.material_b(), field("pairs", i, "material_b"), true);
      if (!a_ok || !b_ok) continue;
      if (p.material_a() == p.material_b()) {
        error(field("pairs", i, "material_b"),
              "must differ from material_a ('" + p.material_a() + "')");
        continue;
      }
      in_pair_.insert(p.material_a());
      in_pair_.insert(p.material_b());
      // Unordered: (a, b) and (b, a) are one interface.
      std::pair<std::string, std::string> key{p.material_a(), p.material_b()};
      if (key.second < key.first) std::swap(key.first, key.second);
      const auto [it, fresh] = seen.emplace(key, i);
      if (!fresh)
        error(field("pairs", i, "material_b"), "duplicate pair " + pair_text(p) +
                                                   " (already surface_tension.pairs[" +
                                                   std::to_string(it->second) + "])");
    }
    std::map<std::string, int> walls_seen;
    for (int i = 0; i < st.walls_size(); ++i) {
      const auto& w = st.walls(i);
      const std::string wf = field("walls", i, "wall");
      if (w.wall().empty()) {
        error(wf, "is required (the name of a wall of the case)");
      } else if (walls_.count(w.wall()) == 0) {
        error(wf, "unknown wall '" + w.wall() + "' (no entry of walls has this name)");
      } else if (const auto [it, fresh] = walls_seen.emplace(w.wall(), i); !fresh) {
        error(wf, "duplicate contact angle for wall '" + w.wall() +
                      "' (already surface_tension.walls[" + std::to_string(it->second) + "])");
      }
      angle_and_liquid("walls", i, w.contact_angle(), w.material());
    }
    // One angle per SOLID material at most: a longer list is wrong whatever it holds.
    if (st.bodies_size() > kMaxMaterials) {
      error("surface_tension.bodies", "has " + std::to_string(st.bodies_size()) +
                                          " entries; at most " + std::to_string(kMaxMaterials) +
                                          " (one per material) are allowed");
      return std::move(errors_);
    }
    std::map<std::string, int> solids_seen;
    for (int i = 0; i < st.bodies_size(); ++i) {
      const auto& b = st.bodies(i);
      const std::string bf = field("bodies", i, "solid_material");
      const auto it = phase_.find(b.solid_material());
      if (b.solid_material().empty()) {
        error(bf, "is required (the name of a SOLID material)");
      } else if (it == phase_.end()) {
        error(bf, "unknown material '" + b.solid_material() + "'");
      } else if (it->second != v1::SOLID) {
        error(bf, "material '" + b.solid_material() +
                      "' is not SOLID (bodies are made of SOLID materials)");
      } else if (const auto [prior, fresh] = solids_seen.emplace(b.solid_material(), i); !fresh) {
        error(bf, "duplicate contact angle for material '" + b.solid_material() +
                      "' (already surface_tension.bodies[" + std::to_string(prior->second) + "])");
      }
      angle_and_liquid("bodies", i, b.contact_angle(), b.material());
    }
    return std::move(errors_);
  }

 private:
  void error(const std::string& f, const std::string& msg) { errors_.push_back({f, msg}); }
  // A contact angle of surface_tension.<list>[i] and the liquid it is measured through.
  void angle_and_liquid(const char* list, int i, double theta, const std::string& liquid) {
    if (!std::isfinite(theta) || !(theta > 0) || !(theta < 180))
      error(field(list, i, "contact_angle"), "must be in (0, 180) degrees; got " + num(theta));
    if (!fluid_material(liquid, field(list, i, "material"), true)) return;
    if (in_pair_.count(liquid) == 0) {
      error(field(list, i, "material"),
            "material '" + liquid + "' has no surface tension (it is in no pair)");
    } else if (free_seen_.count(liquid) != 0 && std::string(list) == "bodies") {
      // The contact-line force is measured at walls only (docs/surface_tension.md).
      error(field(list, i, "material"),
            "material '" + liquid +
                "' has a free surface: contact angles at rigid bodies are not supported at a "
                "free surface yet (use surface_tension.walls; bodies wet it neutrally, 90 "
                "degrees)");
    } else if (free_seen_.count(liquid) != 0 && std::isfinite(theta) &&
               (theta < kMinFreeSurfaceAngle || theta > kMaxFreeSurfaceAngle)) {
      // Measured (docs/surface_tension.md, "Contact angles at a free surface"): 60 and 105
      // settle within 1 degree; 120 settles at about 107 swinging from 100 to 140, 50 swings
      // from 38 to 68, 45 spreads into a film and breaks up.
      error(field(list, i, "contact_angle"),
            "material '" + liquid + "' has a free surface: its contact angle must be in [" +
                num(kMinFreeSurfaceAngle) + ", " + num(kMaxFreeSurfaceAngle) +
                "] degrees (the range validated at a free surface); got " + num(theta));
    }
  }
  static std::string num(double v) { return number_text(v); }
  static std::string pair_text(const v1::SurfaceTension::Pair& p) {
    return "'" + p.material_a() + "' - '" + p.material_b() + "'";
  }
  // Whether `name` is a FLUID material; names the problem otherwise.
  bool fluid_material(const std::string& name, const std::string& f, bool required) {
    if (name.empty()) {
      if (required) error(f, "is required (the name of a FLUID material)");
      return false;
    }
    const auto it = phase_.find(name);
    if (it == phase_.end()) {
      error(f, "unknown material '" + name + "'");
      return false;
    }
    if (it->second == v1::SOLID) {
      error(f, "material '" + name + "' is SOLID; surface tension acts between FLUID materials");
      return false;
    }
    return true;
  }

  // A pair without material_b: material_a against void (solver/physics/
  // surface_tension_free_surface.h), once per material.
  void free_surface(const v1::SurfaceTension::Pair& p, int i) {
    const auto [it, fresh] = free_seen_.emplace(p.material_a(), i);
    if (!fresh) {
      error(field("pairs", i, "material_a"), "duplicate free surface of '" + p.material_a() +
                                                 "' (already surface_tension.pairs[" +
                                                 std::to_string(it->second) + "])");
      return;
    }
    in_pair_.insert(p.material_a());
    // Summation leaves a particle at a free surface with the density of its filled share of
    // the kernel support, about half of rho0 in the outermost row: a pressure of -c^2 rho0 / 2
    // there, against which the Laplace pressure sigma / R is lost.
    if (c_.fluid_model().density() != v1::CONTINUITY && !summation_reported_) {
      summation_reported_ = true;
      error("fluid_model.density",
            "must be CONTINUITY with a free surface under surface tension (surface_tension.pairs[" +
                std::to_string(i) + "] has no material_b): SUMMATION leaves the surface " +
                "particles at about half of rho0");
    }
  }

  const v1::Case& c_;
  bool summation_reported_ = false;
  std::map<std::string, int> free_seen_;
  std::map<std::string, v1::MaterialPhase> phase_;
  std::set<std::string> walls_, in_pair_;
  std::vector<FieldError> errors_;
};

}  // namespace

std::vector<FieldError> validate_surface_tension(const v1::Case& c) {
  if (!c.has_surface_tension()) return {};
  return SurfaceTensionValidator(c).run();
}

}  // namespace sph
