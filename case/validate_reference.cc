#include "case/validate_reference.h"

#include "case/number_text.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace sph {
namespace {

std::string num(double v) {
  return number_text(v);
}

class ReferenceValidator {
 public:
  explicit ReferenceValidator(const v1::Case& c) : c_(c) {}

  std::vector<FieldError> run() {
    const auto& r = c_.reference();
    if (r.has_lattice_period()) positive(r.lattice_period(), "reference.lattice_period");
    switch (r.kind_case()) {
      case v1::Reference::kChannelFlow:
        channel_flow(r.channel_flow());
        break;
      case v1::Reference::kHydrostatic:
        hydrostatic(r.hydrostatic());
        break;
      case v1::Reference::kTaylorGreen:
        taylor_green(r.taylor_green());
        break;
      case v1::Reference::kConduction:
        conduction(r.conduction());
        break;
      case v1::Reference::kSeriesData:
        series_data(r.series_data());
        break;
      case v1::Reference::kRichardson:
        richardson(r.richardson());
        break;
      case v1::Reference::kSeriesPeriod:
        series_period(r.series_period());
        break;
      default:
        error("reference",
              "give one kind: channel_flow, hydrostatic, taylor_green, conduction, series_data, "
              "richardson or series_period");
    }
    return std::move(errors_);
  }

 private:
  void error(const std::string& field, const std::string& msg) { errors_.push_back({field, msg}); }
  void positive(double v, const std::string& field) {
    if (!std::isfinite(v) || v <= 0) error(field, "must be > 0 (got " + num(v) + ")");
  }
  void finite(double v, const std::string& field) {
    if (!std::isfinite(v)) error(field, "must be finite");
  }

  void channel_flow(const v1::ChannelFlowReference& r) {
    const std::string f = "reference.channel_flow.";
    finite(r.lower_wall(), f + "lower_wall");
    positive(r.height(), f + "height");
    positive(r.kinematic_viscosity(), f + "kinematic_viscosity");
    finite(r.body_force(), f + "body_force");
    finite(r.wall_velocity(), f + "wall_velocity");
    if (r.has_velocity_scale())
      positive(r.velocity_scale(), f + "velocity_scale");
    else if (r.body_force() == 0 && r.wall_velocity() == 0)
      error("reference.channel_flow",
            "give body_force or wall_velocity (or velocity_scale): a flow at rest has no "
            "velocity scale to measure the error in");
  }

  void hydrostatic(const v1::HydrostaticReference& r) {
    const std::string f = "reference.hydrostatic.";
    if (c_.dimension() != 2) error("reference.hydrostatic", "is for 2D cases");
    finite(r.bottom(), f + "bottom");
    positive(r.width(), f + "width");
    if (!(r.x_min() < r.x_max()))
      error(f + "x_max",
            "must be larger than x_min (got " + num(r.x_min()) + " and " + num(r.x_max()) + ")");
    const auto& g = c_.gravity().acceleration();
    if (!c_.has_gravity() || std::hypot(g.x(), g.y(), g.z()) == 0)
      error("reference.hydrostatic", "needs gravity (the case has none)");
    if (c_.fluids_size() == 0) error("reference.hydrostatic", "needs a fluid region");
  }

  void taylor_green(const v1::TaylorGreenReference& r) {
    const std::string f = "reference.taylor_green.";
    positive(r.kinematic_viscosity(), f + "kinematic_viscosity");
    positive(r.wavelength(), f + "wavelength");
    if (!std::isfinite(r.fit_start()) || r.fit_start() < 0 || r.fit_start() >= c_.time().end_time())
      error(f + "fit_start", "must be in [0, time.end_time) (got " + num(r.fit_start()) + ")");
    if (!v1::TaylorGreenReference::Measure_IsValid(r.measure()))
      error(f + "measure", "unknown measure");
    if (r.measure() == v1::TaylorGreenReference::VELOCITY_FIELD) {
      positive(r.amplitude(), f + "amplitude");
      if (c_.dimension() != 2) error(f + "measure", "VELOCITY_FIELD is for 2D cases");
    }
  }

  void conduction(const v1::ConductionReference& r) {
    const std::string f = "reference.conduction.";
    finite(r.boundary(), f + "boundary");
    finite(r.boundary_value(), f + "boundary_value");
    finite(r.initial_value(), f + "initial_value");
    if (r.boundary_value() == r.initial_value())
      error(f + "initial_value",
            "must differ from boundary_value (the error is relative to "
            "their difference)");
    positive(r.diffusivity(), f + "diffusivity");
    if (r.has_x_max() && !(r.x_max() > r.boundary()))
      error(f + "x_max", "must be larger than boundary");
    if (r.field().empty() || r.field() == "temperature") {
      if (!c_.has_thermal())
        error(f + "field", "temperature needs heat conduction: add a `thermal { }` block");
    } else if (r.field() == "concentration") {
      if (!c_.has_diffusion())
        error(f + "field", "concentration needs diffusion: add a `diffusion { }` block");
    } else {
      error(f + "field",
            "must be \"temperature\" or \"concentration\" (got \"" + r.field() + "\")");
    }
  }

  // A result series name "group/name" (or "probes/PROBE/name") the case will write.
  void series(const std::string& s, const std::string& field) {
    const auto slash = s.find('/');
    if (s.empty() || slash == std::string::npos || slash == 0 || slash + 1 == s.size()) {
      error(field,
            "must name a result series \"group/name\", e.g. \"diagnostics/max_speed\" (got \"" + s +
                "\")");
      return;
    }
    const std::string group = s.substr(0, slash);
    if (group == "diagnostics") return;
    if (group == "bodies") {
      if (c_.bodies_size() == 0) error(field, "\"" + s + "\" needs rigid bodies in the case");
      return;
    }
    if (group == "phase") {
      if (c_.phase_transitions_size() == 0)
        error(field, "\"" + s + "\" needs phase_transitions in the case");
      return;
    }
    if (group == "probes") {
      const std::string rest = s.substr(slash + 1);
      const auto second = rest.find('/');
      const std::string probe = rest.substr(0, second);
      bool found = false;
      for (const auto& p : c_.probes()) found = found || p.name() == probe;
      if (second == std::string::npos || !found)
        error(field, "\"" + s +
                         "\" does not name a probe series \"probes/NAME/QUANTITY\" of one "
                         "of the case's probes");
      return;
    }
    if (group == "elastic") {
      elastic_series(s.substr(slash + 1), s, field);
      return;
    }
    error(field, "unknown series group '" + group +
                     "' (diagnostics, bodies, probes, phase or elastic; see "
                     "solver/io/result_file.h)");
  }

  // "elastic/BODY/QUANTITY" (solver/elastic/elastic_solid.h): BODY an elastic body's name
  // (body<index> when it has none), QUANTITY displacement (which needs observation points),
  // kinetic_energy or strain_energy.
  void elastic_series(const std::string& rest, const std::string& s, const std::string& field) {
    const auto second = rest.find('/');
    const std::string body = rest.substr(0, second);
    const std::string quantity = second == std::string::npos ? "" : rest.substr(second + 1);
    const v1::ElasticBody* found = nullptr;
    for (int k = 0; k < c_.elastic_bodies_size(); ++k) {
      const auto& e = c_.elastic_bodies(k);
      if ((e.name().empty() ? "body" + std::to_string(k) : e.name()) == body) found = &e;
    }
    if (found == nullptr) {
      error(field, "\"" + s +
                       "\" does not name one of the case's elastic bodies "
                       "(\"elastic/BODY/QUANTITY\")");
      return;
    }
    if (quantity == "displacement") {
      if (found->observation_points_size() == 0)
        error(field, "\"" + s + "\" needs observation_points on elastic body '" + body + "'");
      return;
    }
    if (quantity != "kinetic_energy" && quantity != "strain_energy")
      error(field, "\"" + s +
                       "\": an elastic body writes displacement, kinetic_energy and "
                       "strain_energy");
  }

  // The number of values in one sample of an elastic series, or 0 when not known here.
  int elastic_row(const std::string& s) const {
    if (s.rfind("elastic/", 0) != 0) return 0;
    const std::string rest = s.substr(8);
    const auto second = rest.find('/');
    if (second == std::string::npos) return 0;
    const std::string body = rest.substr(0, second), quantity = rest.substr(second + 1);
    for (int k = 0; k < c_.elastic_bodies_size(); ++k) {
      const auto& e = c_.elastic_bodies(k);
      if ((e.name().empty() ? "body" + std::to_string(k) : e.name()) != body) continue;
      if (quantity == "displacement") return e.observation_points_size() * c_.dimension();
      return 1;
    }
    return 0;
  }

  void series_data(const v1::SeriesDataReference& r) {
    const std::string f = "reference.series_data.";
    series(r.series(), f + "series");
    if (r.component() < 0) error(f + "component", "must be >= 0");
    if (!r.file().empty() && r.times_size() == 0)
      error(f + "file",
            "was not read: load the case from its file (sphctl and sph-worker read "
            "'" +
                r.file() + "' into times and values)");
    else if (r.times_size() < 2)
      error(f + "times", "needs at least two data points (give `file`, or times and values)");
    if (r.times_size() != r.values_size())
      error(f + "values",
            "must have as many entries as times (" + std::to_string(r.times_size()) + ")");
    // Digitised data need not be sorted (a curve read off a figure can step back); the
    // evaluators sample the run at each data time, so the order does not matter.
    for (int i = 0; i < r.times_size(); ++i)
      if (!std::isfinite(r.times(i)) || (i < r.values_size() && !std::isfinite(r.values(i)))) {
        error(f + "values", "must be finite (entry " + std::to_string(i) + ")");
        break;
      }
    if (r.has_time_scale()) positive(r.time_scale(), f + "time_scale");
    if (r.has_value_scale() && (!std::isfinite(r.value_scale()) || r.value_scale() == 0))
      error(f + "value_scale", "must be finite and non-zero");
    if (r.t_max() != 0 && !(r.t_max() > r.t_min()))
      error(f + "t_max", "must be larger than t_min (or 0: to the end of the run)");
    if (!v1::SeriesDataReference::Metric_IsValid(r.metric())) error(f + "metric", "unknown metric");
  }

  void richardson(const v1::RichardsonReference& r) {
    const std::string f = "reference.richardson.";
    series(r.series(), f + "series");
    if (r.component() < 0) error(f + "component", "must be >= 0");
    if (r.has_time() &&
        (!std::isfinite(r.time()) || r.time() < 0 || r.time() > c_.time().end_time()))
      error(f + "time", "must be in [0, time.end_time]");
    if (r.has_order()) positive(r.order(), f + "order");
    if (r.has_scale()) positive(r.scale(), f + "scale");
    finite(r.offset(), f + "offset");
  }

  void series_period(const v1::SeriesPeriodReference& r) {
    const std::string f = "reference.series_period.";
    const std::size_t before = errors_.size();
    series(r.series(), f + "series");
    if (r.component() < 0) {
      error(f + "component", "must be >= 0");
    } else if (const int row = elastic_row(r.series());
               errors_.size() == before && row > 0 && r.component() >= row) {
      error(f + "component", "must be below " + std::to_string(row) + ": \"" + r.series() +
                                 "\" has " + std::to_string(row) +
                                 " values per sample (point * dimension + axis)");
    }
    positive(r.period(), f + "period");
    finite(r.mean(), f + "mean");
    // Bounded so that the crossing index 2 (first_cycle + cycles) stays far from overflow.
    constexpr int kMaxCycles = 1000000;
    const int first = r.has_first_cycle() ? r.first_cycle() : 1;
    const int cycles = r.has_cycles() ? r.cycles() : 1;
    if (first < 1 || first > kMaxCycles)
      error(f + "first_cycle", "must be in [1, " + std::to_string(kMaxCycles) + "] (got " +
                                   std::to_string(first) + ")");
    if (cycles < 1 || cycles > kMaxCycles)
      error(f + "cycles", "must be in [1, " + std::to_string(kMaxCycles) + "] (got " +
                              std::to_string(cycles) + ")");
    if (errors_.size() != before) return;
    // The exact period is the least the run must cover; a coarse level's period is longer.
    const double needed = (first - 1 + cycles) * r.period();
    if (c_.time().end_time() < needed)
      error("time.end_time", "must be at least " + num(needed) +
                                 " s for reference.series_period (" +
                                 std::to_string(first - 1 + cycles) + " periods of " +
                                 num(r.period()) + " s); got " + num(c_.time().end_time()));
    // Ten samples per period leave the linearly interpolated crossing times within about 0.1%
    // of the period (the interpolation error of a sine at its zero is O((omega dt)^3)).
    const double interval = c_.output().series_interval() > 0 ? c_.output().series_interval()
                                                              : c_.time().end_time() / 100;
    if (interval > r.period() / 10)
      error("output.series_interval",
            "must be at most reference.series_period.period / 10 = " + num(r.period() / 10) +
                " s so that the crossings are resolved (got " + num(interval) +
                (c_.output().series_interval() > 0 ? " s)" : " s, the default end_time / 100)"));
  }

  const v1::Case& c_;
  std::vector<FieldError> errors_;
};

}  // namespace

std::vector<FieldError> validate_reference(const v1::Case& c) {
  if (!c.has_reference()) return {};
  return ReferenceValidator(c).run();
}

}  // namespace sph
