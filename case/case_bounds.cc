#include "case/case_bounds.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>

#include "case/case_limits.h"
#include "case/number_text.h"

namespace sph {
namespace {

namespace pb = google::protobuf;

std::string idx(const std::string& base, int i) {
  return base + "[" + std::to_string(i) + "]";
}

// Calls fn(child) for each shape directly inside s.
template <class Fn>
void for_each_part(const v1::Shape& s, Fn&& fn) {
  switch (s.kind_case()) {
    case v1::Shape::kUnion:
      for (const auto& p : s.union_().shapes()) fn(p);
      break;
    case v1::Shape::kIntersection:
      for (const auto& p : s.intersection().shapes()) fn(p);
      break;
    case v1::Shape::kDifference:
      if (s.difference().has_base()) fn(s.difference().base());
      for (const auto& p : s.difference().subtract()) fn(p);
      break;
    case v1::Shape::kShell:
      if (s.shell().has_inner()) fn(s.shell().inner());
      break;
    default:
      break;
  }
}

std::size_t string_limit(const pb::FieldDescriptor* f) {
  if (f->name() == "description") return kMaxDescriptionBytes;
  if (f->name() == "file") return kMaxPathBytes;
  return kMaxNameBytes;
}

// One value of a string or floating-point field: its length against the field's limit, or
// whether it is a number. No field of a case means anything by NaN or infinity, and the checks
// after these compare numbers, which NaN passes silently (an initial temperature of NaN was
// accepted until every number was checked here).
void check_value(const pb::Message& m, const pb::FieldDescriptor* f, int i,
                 const std::string& field, std::vector<FieldError>& errors) {
  const pb::Reflection* r = m.GetReflection();
  if (f->cpp_type() == pb::FieldDescriptor::CPPTYPE_STRING) {
    std::string scratch;
    const std::string& v = i < 0 ? r->GetStringReference(m, f, &scratch)
                                 : r->GetRepeatedStringReference(m, f, i, &scratch);
    const std::size_t limit = string_limit(f);
    if (v.size() > limit)
      errors.push_back({field, "is " + std::to_string(v.size()) + " bytes long; the limit is " +
                                   std::to_string(limit)});
    return;
  }
  double v = 0;
  if (f->cpp_type() == pb::FieldDescriptor::CPPTYPE_DOUBLE)
    v = i < 0 ? r->GetDouble(m, f) : r->GetRepeatedDouble(m, f, i);
  else if (f->cpp_type() == pb::FieldDescriptor::CPPTYPE_FLOAT)
    v = static_cast<double>(i < 0 ? r->GetFloat(m, f) : r->GetRepeatedFloat(m, f, i));
  else
    return;
  if (!std::isfinite(v))
    errors.push_back({field, "is " + number_text(v) + "; every number must be finite"});
}

// Whether messages of type d hold scalars only (Vec3, a table row): a million of them in a
// point set are checked in place, their path spelled out only for an error.
bool holds_only_scalars(const pb::Descriptor* d) {
  for (int i = 0; i < d->field_count(); ++i)
    if (d->field(i)->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) return false;
  return true;
}

void check_scalars(const pb::Message& m, const std::string& path, std::vector<FieldError>& errors) {
  const pb::Reflection* r = m.GetReflection();
  std::vector<const pb::FieldDescriptor*> fields;
  r->ListFields(m, &fields);
  for (const auto* f : fields) {
    const std::string fp = path + "." + f->name();
    if (f->is_repeated()) {
      for (int k = 0; k < r->FieldSize(m, f); ++k) check_value(m, f, k, idx(fp, k), errors);
    } else {
      check_value(m, f, -1, fp, errors);
    }
  }
}

// Whether one scalar-only message needs its path: a value that check_value would refuse.
bool scalars_need_check(const pb::Message& m) {
  const pb::Reflection* r = m.GetReflection();
  const pb::Descriptor* d = m.GetDescriptor();
  for (int i = 0; i < d->field_count(); ++i) {
    const auto* f = d->field(i);
    const auto type = f->cpp_type();
    if (f->is_repeated()) {
      if (r->FieldSize(m, f) > 0) return true;  // rare in such messages: the slow path
    } else if (type == pb::FieldDescriptor::CPPTYPE_DOUBLE) {
      if (!std::isfinite(r->GetDouble(m, f))) return true;
    } else if (type == pb::FieldDescriptor::CPPTYPE_FLOAT) {
      if (!std::isfinite(r->GetFloat(m, f))) return true;
    } else if (type == pb::FieldDescriptor::CPPTYPE_STRING) {
      std::string scratch;
      if (r->GetStringReference(m, f, &scratch).size() > string_limit(f)) return true;
    }
  }
  return false;
}

// Every string and floating-point field of the case, walked with an explicit stack. Stops
// listing after kMaxFieldErrors: a case of a million NaN points needs one line, not a million.
void check_fields(const v1::Case& c, std::vector<FieldError>& errors) {
  constexpr std::size_t kMaxFieldErrors = 100;
  std::vector<std::pair<const pb::Message*, std::string>> stack{{&c, ""}};
  std::vector<const pb::FieldDescriptor*> fields;
  const std::size_t first = errors.size();
  while (!stack.empty() && errors.size() - first < kMaxFieldErrors) {
    const pb::Message* m = stack.back().first;
    const std::string path = std::move(stack.back().second);
    stack.pop_back();
    const pb::Reflection* r = m->GetReflection();
    fields.clear();
    r->ListFields(*m, &fields);
    for (const auto* f : fields) {
      const std::string fp = path.empty() ? f->name() : path + "." + f->name();
      if (f->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
        if (f->is_repeated() && holds_only_scalars(f->message_type())) {
          for (int i = 0; i < r->FieldSize(*m, f) && errors.size() - first < kMaxFieldErrors; ++i) {
            const pb::Message& item = r->GetRepeatedMessage(*m, f, i);
            if (scalars_need_check(item)) check_scalars(item, idx(fp, i), errors);
          }
        } else if (f->is_repeated()) {
          for (int i = r->FieldSize(*m, f) - 1; i >= 0; --i)
            stack.emplace_back(&r->GetRepeatedMessage(*m, f, i), idx(fp, i));
        } else {
          stack.emplace_back(&r->GetMessage(*m, f), fp);
        }
      } else if (f->is_repeated()) {
        for (int i = 0; i < r->FieldSize(*m, f); ++i) check_value(*m, f, i, idx(fp, i), errors);
      } else {
        check_value(*m, f, -1, fp, errors);
      }
    }
  }
  if (errors.size() - first >= kMaxFieldErrors)
    errors.push_back({"", "more fields than these break their bounds; only the first " +
                              std::to_string(kMaxFieldErrors) + " are listed"});
}

void check_count(int n, int limit, const std::string& field, const std::string& what,
                 std::vector<FieldError>& errors) {
  if (n > limit)
    errors.push_back(
        {field, std::to_string(n) + " " + what + "; the limit is " + std::to_string(limit)});
}

void check_table(int times, int values, const std::string& field, std::vector<FieldError>& errors) {
  check_count(times, kMaxTableEntries, field + ".times", "entries", errors);
  check_count(values, kMaxTableEntries, field + ".values", "entries", errors);
}

void check_time_function(const v1::TimeFunction& tf, const std::string& field,
                         std::vector<FieldError>& errors) {
  if (tf.has_piecewise_linear())
    check_table(tf.piecewise_linear().times_size(), tf.piecewise_linear().values_size(),
                field + ".piecewise_linear", errors);
  if (tf.has_piecewise_constant())
    check_table(tf.piecewise_constant().times_size(), tf.piecewise_constant().values_size(),
                field + ".piecewise_constant", errors);
}

void check_motion(const v1::Motion& m, const std::string& field, std::vector<FieldError>& errors) {
  check_time_function(m.velocity_x(), field + ".velocity_x", errors);
  check_time_function(m.velocity_y(), field + ".velocity_y", errors);
  check_time_function(m.velocity_z(), field + ".velocity_z", errors);
  check_time_function(m.angular_velocity(), field + ".angular_velocity", errors);
}

void check_counts(const v1::Case& c, std::vector<FieldError>& errors) {
  check_count(c.materials_size(), kMaxMaterials, "materials", "materials", errors);
  // The region that takes fluids, walls and bodies together over the limit is named.
  if (const int regions = c.fluids_size() + c.walls_size() + c.bodies_size();
      regions > kMaxRegions) {
    int k = kMaxRegions;  // index of the first region over the limit, in fluids, walls, bodies
    const std::string field = k < c.fluids_size() ? idx("fluids", k)
                              : (k -= c.fluids_size()) < c.walls_size()
                                  ? idx("walls", k)
                                  : idx("bodies", k - c.walls_size());
    errors.push_back({field, "the case has " + std::to_string(regions) +
                                 " regions (fluids, walls and bodies together); the limit is " +
                                 std::to_string(kMaxRegions)});
  }
  check_count(c.phase_transitions_size(), kMaxPhaseTransitions, "phase_transitions",
              "phase transitions", errors);
  check_count(c.probes_size(), kMaxProbes, "probes", "probes", errors);
  check_count(c.open_boundaries_size(), kMaxOpenBoundaries, "open_boundaries", "open boundaries",
              errors);
  check_count(c.output().times_size(), kMaxTableEntries, "output.times", "entries", errors);
  if (c.reference().has_series_data())
    check_table(c.reference().series_data().times_size(), c.reference().series_data().values_size(),
                "reference.series_data", errors);
  for (int i = 0; i < c.walls_size(); ++i) {
    const auto& w = c.walls(i);
    const std::string f = idx("walls", i);
    if (w.has_motion()) check_motion(w.motion(), f + ".motion", errors);
    if (w.has_temperature())
      check_time_function(w.temperature().value(), f + ".temperature.value", errors);
    if (w.has_concentration())
      check_time_function(w.concentration().value(), f + ".concentration.value", errors);
  }
  for (int i = 0; i < c.bodies_size(); ++i)
    if (c.bodies(i).has_motion())
      check_motion(c.bodies(i).motion(), idx("bodies", i) + ".motion", errors);
  for (int i = 0; i < c.elastic_bodies_size(); ++i)
    for (int j = 0; j < c.elastic_bodies(i).constraints_size(); ++j)
      if (c.elastic_bodies(i).constraints(j).has_motion())
        check_motion(c.elastic_bodies(i).constraints(j).motion(),
                     idx(idx("elastic_bodies", i) + ".constraints", j) + ".motion", errors);
}

// Depth, count, vertices and points of every region's shape; the case-wide totals are charged
// to the region that takes them over their limit.
void check_shapes(const v1::Case& c, std::vector<FieldError>& errors) {
  ShapeTreeSize total;
  bool shapes_over = false, vertices_over = false, points_over = false, triangles_over = false,
       nodes_over = false;
  auto region = [&](const v1::Shape& s, const std::string& field) {
    const ShapeTreeSize n = measure_shape(s);
    if (n.depth > kMaxShapeDepth) errors.push_back({field, shape_depth_error(n.depth)});
    total.shapes += n.shapes;
    total.polygon_vertices += n.polygon_vertices;
    total.points += n.points;
    total.mesh_triangles += n.mesh_triangles;
    total.grid_nodes += n.grid_nodes;
    if (!shapes_over && total.shapes > kMaxShapes) {
      shapes_over = true;
      errors.push_back({field, "the case has " + std::to_string(total.shapes) +
                                   " shapes up to here (nested ones included); the limit is " +
                                   std::to_string(kMaxShapes)});
    }
    if (!vertices_over && total.polygon_vertices > kMaxPolygonVertices) {
      vertices_over = true;
      errors.push_back({field, "the case has " + std::to_string(total.polygon_vertices) +
                                   " polygon vertices up to here; the limit is " +
                                   std::to_string(kMaxPolygonVertices)});
    }
    if (!triangles_over && total.mesh_triangles > kMaxMeshTriangles) {
      triangles_over = true;
      errors.push_back({field, "the case has " + std::to_string(total.mesh_triangles) +
                                   " mesh triangles up to here; the limit is " +
                                   std::to_string(kMaxMeshTriangles)});
    }
    if (!nodes_over && total.grid_nodes > kMaxDistanceGridNodes) {
      nodes_over = true;
      errors.push_back({field, "the case has " + std::to_string(total.grid_nodes) +
                                   " distance-grid nodes up to here; the limit is " +
                                   std::to_string(kMaxDistanceGridNodes)});
    }
    if (!points_over && total.points > kMaxPointsPerCase) {
      points_over = true;
      errors.push_back({field, "the case has " + std::to_string(total.points) +
                                   " explicit points up to here; the limit is " +
                                   std::to_string(kMaxPointsPerCase)});
    }
  };
  for (int i = 0; i < c.fluids_size(); ++i)
    region(c.fluids(i).shape(), idx("fluids", i) + ".shape");
  for (int i = 0; i < c.walls_size(); ++i) region(c.walls(i).shape(), idx("walls", i) + ".shape");
  for (int i = 0; i < c.bodies_size(); ++i)
    region(c.bodies(i).shape(), idx("bodies", i) + ".shape");
  for (int i = 0; i < c.elastic_bodies_size(); ++i) {
    const auto& b = c.elastic_bodies(i);
    region(b.shape(), idx("elastic_bodies", i) + ".shape");
    for (int j = 0; j < b.constraints_size(); ++j)
      region(b.constraints(j).region(),
             idx(idx("elastic_bodies", i) + ".constraints", j) + ".region");
  }
}

double component(const v1::Vec3& v, int a) {
  return a == 0 ? v.x() : a == 1 ? v.y() : v.z();
}

// dx, domain and lattice_origin: finite, within kMaxCoordinate, and every domain corner at
// most kMaxLatticeCellsPerAxis cells of dx from the lattice origin, before any code divides a
// length by dx and converts it to an integer.
void check_lattice_range(const v1::Case& c, std::vector<FieldError>& errors) {
  const double dx = c.dx();
  const bool dx_usable = std::isfinite(dx) && dx > 0;  // else validation names it
  if (dx_usable && dx < kMinDx)
    errors.push_back({"dx", "is " + count_text(dx) + " m; the smallest particle spacing is " +
                                count_text(kMinDx) + " m"});
  if (dx_usable && dx > kMaxCoordinate)
    errors.push_back(
        {"dx", "is " + count_text(dx) + " m; the largest is " + count_text(kMaxCoordinate) + " m"});
  const int dim = c.dimension() == 3 ? 3 : 2;
  const char* axes = "xyz";
  bool coordinates_ok = true;
  auto coordinate = [&](double v, const std::string& field) {
    if (std::isfinite(v) && std::abs(v) > kMaxCoordinate) {
      errors.push_back({field, "is " + count_text(v) + " m; coordinates must lie within +-" +
                                   count_text(kMaxCoordinate) + " m"});
      coordinates_ok = false;
    }
    if (!std::isfinite(v)) coordinates_ok = false;  // validation names it
  };
  for (int a = 0; a < dim; ++a) {
    coordinate(component(c.domain().lo(), a), std::string("domain.lo.") + axes[a]);
    coordinate(component(c.domain().hi(), a), std::string("domain.hi.") + axes[a]);
    coordinate(component(c.lattice_origin(), a), std::string("lattice_origin.") + axes[a]);
  }
  if (!dx_usable || !coordinates_ok) return;
  for (int a = 0; a < dim; ++a) {
    const double origin = component(c.lattice_origin(), a);
    for (const bool hi : {false, true}) {
      const double v = component(hi ? c.domain().hi() : c.domain().lo(), a);
      const double cells = std::abs(v - origin) / dx;
      if (cells > kMaxLatticeCellsPerAxis) {
        errors.push_back({std::string(hi ? "domain.hi." : "domain.lo.") + axes[a],
                          "lies " + count_text(cells) + " cells of dx = " + number_text(dx) +
                              " from lattice_origin." + axes[a] + "; the limit is 2^31 (" +
                              count_text(kMaxLatticeCellsPerAxis) +
                              ") cells along each axis: increase dx or shrink the domain"});
        break;
      }
    }
  }
}

}  // namespace

ShapeTreeSize measure_shape(const v1::Shape& s) {
  ShapeTreeSize n;
  std::vector<std::pair<const v1::Shape*, int>> stack{{&s, 1}};
  while (!stack.empty()) {
    // Not a structured binding: clang (the fuzz build) cannot capture one in the lambda below.
    const v1::Shape* shape = stack.back().first;
    const int depth = stack.back().second;
    stack.pop_back();
    n.shapes += 1;
    n.depth = std::max(n.depth, depth);
    if (shape->has_polygon()) n.polygon_vertices += shape->polygon().vertices_size();
    if (shape->has_points()) n.points += shape->points().points_size();
    if (shape->has_mesh()) n.mesh_triangles += shape->mesh().triangles_size() / 3;
    if (shape->has_distance_grid()) n.grid_nodes += shape->distance_grid().values_size();
    for_each_part(*shape, [&](const v1::Shape& p) { stack.emplace_back(&p, depth + 1); });
  }
  return n;
}

std::string shape_depth_error(int depth) {
  if (depth <= kMaxShapeDepth) return "";
  return "shapes nest " + std::to_string(depth) + " deep; the limit is " +
         std::to_string(kMaxShapeDepth);
}

std::vector<FieldError> check_case_bounds(const v1::Case& c) {
  std::vector<FieldError> errors;
  check_fields(c, errors);
  check_counts(c, errors);
  check_shapes(c, errors);
  check_lattice_range(c, errors);
  return errors;
}

std::string count_text(double v) {
  char buf[64];
  if (std::abs(v) < 1e6 && v == std::round(v))
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, std::abs(v) < 1e6 ? "%.6g" : "%.3g", v);
  // "3.1e+08" -> "3.1e8", "1e-300" stays
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string exponent = s.substr(e + 1);
  const bool negative = !exponent.empty() && exponent[0] == '-';
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return s.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

}  // namespace sph
