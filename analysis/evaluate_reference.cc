#include "analysis/evaluate_reference.h"

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "analysis/channel_flow.h"
#include "analysis/conduction.h"
#include "analysis/hydrostatic.h"
#include "analysis/result_reader.h"
#include "analysis/richardson.h"
#include "analysis/series_data.h"
#include "analysis/series_period.h"
#include "analysis/taylor_green.h"
#include "case/materials.h"
#include "case/number_text.h"
#include "case/reference_table.h"

namespace sph::analysis {
namespace {

// Concatenation without `"literal" + std::string&&`, which GCC 12 warns about falsely
// (-Wrestrict).
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string s;
  for (const auto p : parts) s.append(p);
  return s;
}

// The scalar series a series_data or richardson reference names, with its sample times.
void read_scalar_series(const ResultReader& rr, const std::string& name, int component, bool sum,
                        const std::string& field, std::vector<double>& t, std::vector<double>& v) {
  if (!rr.has_series(name))
    throw std::runtime_error(field + ".series: the result has no series '" + name + "'");
  t = rr.series_time(name);
  v = series_component(rr.series(name), t.size(), component, sum, field);
}

Measurement hydrostatic(const v1::Case& c, const ResultReader& rr) {
  const auto mats = resolve_materials(c);
  const int m = material_index(mats, c.fluids(0).material());
  const double rho0 = mats.at(static_cast<std::size_t>(m)).rho0;
  const auto& a = c.gravity().acceleration();
  return hydrostatic_error(rr.last(), c.reference().hydrostatic(), rho0,
                           std::hypot(a.x(), a.y(), a.z()), c.dx());
}

Measurement richardson_quantity(const v1::Case& c, const ResultReader& rr) {
  const auto& r = c.reference().richardson();
  std::vector<double> t, v;
  read_scalar_series(rr, r.series(), r.component(), r.sum_components(), "reference.richardson", t,
                     v);
  if (t.empty()) throw std::runtime_error("reference.richardson.series: the series is empty");
  const double at = r.has_time() ? r.time() : t.back();
  if (at > t.back() * (1 + 1e-9) + 1e-300)
    throw std::runtime_error(
        cat({"reference.richardson.time: ", number_text(at),
             " is after the run's last sample (t = ", number_text(t.back()), ")"}));
  Measurement m;
  m.quantity = interpolate(t, v, at) - r.offset();
  m.detail = cat(
      {r.series(), r.sum_components() ? " (sum)" : cat({"[", std::to_string(r.component()), "]"}),
       " at t = ", number_text(at), r.offset() != 0 ? cat({" - ", number_text(r.offset())}) : "",
       ": ", number_text(m.quantity)});
  return m;
}

}  // namespace

Measurement evaluate_reference(const v1::Case& c, const std::string& result_h5) {
  if (!c.has_reference()) throw std::runtime_error("reference: the case has none");
  const ResultReader rr(result_h5);
  const auto& ref = c.reference();
  switch (ref.kind_case()) {
    case v1::Reference::kChannelFlow:
      return channel_flow_error(rr.last(), ref.channel_flow());
    case v1::Reference::kHydrostatic:
      return hydrostatic(c, rr);
    case v1::Reference::kTaylorGreen: {
      const auto& r = ref.taylor_green();
      const Measurement rate =
          taylor_green_error(rr.series("diagnostics/time"), rr.series("diagnostics/max_speed"), r);
      if (r.measure() != v1::TaylorGreenReference::VELOCITY_FIELD) return rate;
      return taylor_green_field_error(rr.last(), r, rate.quantity);
    }
    case v1::Reference::kConduction: {
      const auto& r = ref.conduction();
      const int k = rr.snapshot_count() - 1;
      const std::string field = r.field().empty() ? "temperature" : r.field();
      return conduction_error(rr.snapshot(k), rr.snapshot_field(k, field), r);
    }
    case v1::Reference::kSeriesData: {
      const auto& r = ref.series_data();
      std::vector<double> t, v;
      read_scalar_series(rr, r.series(), r.component(), false, "reference.series_data", t, v);
      return series_data_error(t, v, r);
    }
    case v1::Reference::kRichardson:
      return richardson_quantity(c, rr);
    case v1::Reference::kSeriesPeriod: {
      const auto& r = ref.series_period();
      std::vector<double> t, v;
      read_scalar_series(rr, r.series(), r.component(), false, "reference.series_period", t, v);
      return series_period_error(t, v, r);
    }
    default:
      throw std::runtime_error("reference: no kind given");
  }
}

std::string complete_richardson(const v1::Case& c, const std::vector<double>& dx,
                                std::vector<Measurement>& levels) {
  if (!c.has_reference() || !c.reference().has_richardson()) return "";
  const auto& r = c.reference().richardson();
  std::vector<double> h, q;
  std::vector<std::size_t> which;
  for (std::size_t k = 0; k < levels.size() && k < dx.size(); ++k)
    if (std::isfinite(levels[k].quantity)) {
      h.push_back(dx[k]);
      q.push_back(levels[k].quantity);
      which.push_back(k);
    }
  const auto est =
      richardson_extrapolate(h, q, r.has_order() ? std::optional<double>(r.order()) : std::nullopt,
                             r.has_scale() ? std::optional<double>(r.scale()) : std::nullopt);
  if (!est.ok) return "Richardson extrapolation: " + est.problem;
  for (std::size_t j = 0; j < which.size(); ++j) {
    auto& m = levels[which[j]];
    m.error = est.errors[j];
    m.detail += "; q* = " + number_text(est.extrapolated) + " (order " + number_text(est.order) +
                (est.order_estimated ? ", estimated from the three finest levels)" : ", assumed)");
  }
  return "";
}

std::string describe_reference(const v1::Case& c) {
  const auto& ref = c.reference();
  switch (ref.kind_case()) {
    case v1::Reference::kChannelFlow:
      return cat(
          {"mean |u_x - u_exact| / u_ref over the fluid at the end time (analytic start-up "
           "channel flow, u_ref = ",
           number_text(channel_flow_velocity_scale(ref.channel_flow())), ")"});
    case v1::Reference::kHydrostatic:
      return "|p_bottom / (rho g (H + dx/2)) - 1|, first wall layer under the tank bottom at the "
             "end time (analytic)";
    case v1::Reference::kTaylorGreen:
      if (ref.taylor_green().measure() == v1::TaylorGreenReference::VELOCITY_FIELD)
        return "mean |u - u_exact| / (U exp(-2 nu k^2 t)) over the fluid at the end time "
               "(analytic Taylor-Green field; the quantity column is the fitted decay rate)";
      return cat({"|decay rate / (-2 nu k^2) - 1|, rate fitted to log max|u| for t >= ",
                  number_text(ref.taylor_green().fit_start()), " (analytic)"});
    case v1::Reference::kConduction:
      return "max |T - T_erf| / |T_b - T_0| at the end time (analytic erf profile)";
    case v1::Reference::kSeriesData: {
      const auto& r = ref.series_data();
      const std::string q = cat({r.series(), "[", std::to_string(r.component()), "]"});
      return r.metric() == v1::SeriesDataReference::WINDOW_MEAN
                 ? cat({"|mean of ", q,
                        " / mean of the data - 1| over the window (reference data)"})
                 : cat({"mean |", q, " / data - 1| over the data points (reference data)"});
    }
    case v1::Reference::kRichardson: {
      const auto& r = ref.richardson();
      return cat(
          {"|q - q*| / |q*| with q = ", r.series(),
           r.sum_components() ? " summed over components"
                              : cat({"[", std::to_string(r.component()), "]"}),
           r.has_time() ? cat({" at t = ", number_text(r.time())}) : " at the end",
           r.offset() != 0 ? cat({" minus ", number_text(r.offset())}) : "",
           ", q* by Richardson extrapolation from the finest levels",
           r.has_order() ? cat({" with order ", number_text(r.order())}) : " (order estimated)"});
    }
    case v1::Reference::kSeriesPeriod: {
      const auto& r = ref.series_period();
      const int first = r.has_first_cycle() ? r.first_cycle() : 1;
      const int cycles = r.has_cycles() ? r.cycles() : 1;
      const std::string which =
          cycles == 1 ? (first == 1 ? std::string("the first period")
                                    : cat({"the period of cycle ", std::to_string(first)}))
                      : cat({"the mean period of cycles ", std::to_string(first), " to ",
                             std::to_string(first + cycles - 1)});
      return cat({"|T / T_exact - 1|, T ", which, " of ", r.series(), "[",
                  std::to_string(r.component()), "] from its crossings of ", number_text(r.mean()),
                  " (linear interpolation), T_exact = ", number_text(r.period()), " s"});
    }
    default:
      return "(no reference)";
  }
}

}  // namespace sph::analysis
