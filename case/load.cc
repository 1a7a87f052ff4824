#include "case/load.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "case/case_bounds.h"
#include "case/case_limits.h"
#include "case/data_lines.h"
#include "case/distance_grid/read_distance_grid.h"
#include "case/mesh/triangle_mesh.h"
#include "case/reference_data.h"
#include "case/text_nesting.h"

namespace sph {
namespace {

class CollectErrors : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, google::protobuf::io::ColumnNumber column,
                const std::string& message) override {
    if (!text.empty()) text += "; ";
    text += "line " + std::to_string(line + 1) + ", column " + std::to_string(column + 1) + ": " +
            message;
    if (message.find("recursion limit") != std::string::npos) too_deep = true;
  }
  std::string text;
  bool too_deep = false;
};

// A data file named in a case: relative paths are relative to the case file's folder.
std::filesystem::path beside_case(const std::string& base, const std::string& file) {
  std::filesystem::path p(file);
  return p.is_relative() ? std::filesystem::path(base) / p : p;
}

// Reads "x y [z]" lines, at most `limit` points (the smaller of the per-file and the case's
// remaining budget; `limit_text` says which), so that a huge file is refused, not read whole.
std::vector<v1::Vec3> read_point_file(const std::string& path, const std::string& field, int limit,
                                      const std::string& limit_text) {
  std::ifstream in(path);
  if (!in) throw CaseLoadError(field + ": cannot read point file '" + path + "'");
  std::vector<v1::Vec3> points;
  DataLines lines(in, path);
  std::string line;
  try {
    while (lines.next(line)) {
      auto hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      double xyz[3] = {0, 0, 0};
      int n = 0;
      const char* at = line.c_str();
      while (n < 3) {
        char* end = nullptr;
        const double v = std::strtod(at, &end);
        if (end == at) break;
        xyz[n++] = v;
        at = end;
      }
      while (std::isspace(static_cast<unsigned char>(*at))) ++at;
      if (n == 0 && *at == '\0') continue;
      if (n < 2 || *at != '\0')
        throw CaseLoadError(field + ": " + path + ":" + std::to_string(lines.line_number()) +
                            ": expected 'x y' or 'x y z'");
      if (static_cast<int>(points.size()) >= limit)
        throw CaseLoadError(field + ": " + path + " has more than " + std::to_string(limit) +
                            " points; " + limit_text);
      v1::Vec3 p;
      p.set_x(xyz[0]);
      p.set_y(xyz[1]);
      p.set_z(xyz[2]);
      points.push_back(p);
    }
  } catch (const CaseLoadError&) {
    throw;
  } catch (const std::exception& e) {
    throw CaseLoadError(field + ": " + e.what());
  }
  return points;
}

// Explicit points, polygon vertices, mesh triangles and distance-grid nodes the case holds
// (inlined or read so far), for the per-case budgets.
struct PointBudget {
  int used = 0;
  int polygon_vertices = 0;
  std::int64_t mesh_triangles = 0;
  std::int64_t grid_nodes = 0;
  int dimension = 3;  // of the case: the axes a distance grid's dataset must have
};

// Recursion over the shape tree: callers check its depth first (measure_shape).
void inline_shape(v1::Shape& s, const std::string& base, const std::string& field,
                  PointBudget& budget) {
  switch (s.kind_case()) {
    case v1::Shape::kPoints: {
      auto* ps = s.mutable_points();
      if (!ps->file().empty()) {
        const std::filesystem::path p = beside_case(base, ps->file());
        const int left = std::max(0, kMaxPointsPerCase - budget.used);
        const bool per_file = kMaxPointsPerFile <= left;
        const std::string limit_text =
            per_file
                ? "the limit is " + std::to_string(kMaxPointsPerFile) + " points per file"
                : "the limit is " + std::to_string(kMaxPointsPerCase) + " points per case and " +
                      std::to_string(budget.used) + " are already in it";
        auto points = read_point_file(p.string(), field + ".points.file",
                                      std::min(kMaxPointsPerFile, left), limit_text);
        budget.used += static_cast<int>(points.size());
        for (auto& v : points) *ps->add_points() = std::move(v);
        ps->clear_file();
      }
      break;
    }
    case v1::Shape::kPolygon: {
      auto* poly = s.mutable_polygon();
      if (!poly->file().empty()) {
        const std::filesystem::path p = beside_case(base, poly->file());
        const int left = std::max(0, kMaxPolygonVertices - budget.polygon_vertices);
        auto vertices =
            read_point_file(p.string(), field + ".polygon.file", left,
                            "the limit is " + std::to_string(kMaxPolygonVertices) +
                                " polygon vertices per case and " +
                                std::to_string(budget.polygon_vertices) + " are already in it");
        budget.polygon_vertices += static_cast<int>(vertices.size());
        for (auto& v : vertices) *poly->add_vertices() = std::move(v);
        poly->clear_file();
      }
      break;
    }
    case v1::Shape::kMesh: {
      auto* mesh = s.mutable_mesh();
      if (!mesh->file().empty()) {
        const std::filesystem::path p = beside_case(base, mesh->file());
        const auto left = static_cast<std::size_t>(
            std::max<std::int64_t>(0, kMaxMeshTriangles - budget.mesh_triangles));
        try {
          read_stl(p.string(), left, *mesh);
        } catch (const std::runtime_error& e) {
          throw CaseLoadError(field + ".mesh.file: " + e.what());
        }
        budget.mesh_triangles += mesh->triangles_size() / 3;
        mesh->clear_file();
      }
      break;
    }
    case v1::Shape::kDistanceGrid: {
      auto* grid = s.mutable_distance_grid();
      if (!grid->file().empty()) {
        const std::filesystem::path p = beside_case(base, grid->file());
        // A case of another dimension is refused by validation; read as 3D meanwhile.
        const int dim = budget.dimension == 2 ? 2 : 3;
        budget.grid_nodes -= grid->values_size();  // the file's values replace these
        const auto left = static_cast<std::size_t>(
            std::max<std::int64_t>(0, kMaxDistanceGridNodes - budget.grid_nodes));
        try {
          read_distance_grid(p.string(), dim, left, *grid);
        } catch (const std::runtime_error& e) {
          throw CaseLoadError(field + ".distance_grid.file: " + e.what());
        }
        budget.grid_nodes += grid->values_size();
        grid->clear_file();
      }
      break;
    }
    case v1::Shape::kUnion:
      for (int i = 0; i < s.union_().shapes_size(); ++i)
        inline_shape(*s.mutable_union_()->mutable_shapes(i), base,
                     field + ".union.shapes[" + std::to_string(i) + "]", budget);
      break;
    case v1::Shape::kIntersection:
      for (int i = 0; i < s.intersection().shapes_size(); ++i)
        inline_shape(*s.mutable_intersection()->mutable_shapes(i), base,
                     field + ".intersection.shapes[" + std::to_string(i) + "]", budget);
      break;
    case v1::Shape::kDifference:
      inline_shape(*s.mutable_difference()->mutable_base(), base, field + ".difference.base",
                   budget);
      for (int i = 0; i < s.difference().subtract_size(); ++i)
        inline_shape(*s.mutable_difference()->mutable_subtract(i), base,
                     field + ".difference.subtract[" + std::to_string(i) + "]", budget);
      break;
    case v1::Shape::kShell:
      inline_shape(*s.mutable_shell()->mutable_inner(), base, field + ".shell.inner", budget);
      break;
    default:
      break;
  }
}

}  // namespace

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseLoadError("cannot read '" + path + "'");
  // Read in pieces and stop past the limit, so that a huge file is not read whole.
  std::string text;
  char chunk[65536];
  while (in) {
    in.read(chunk, sizeof chunk);
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxCaseFileBytes)
      throw CaseLoadError(path + ": the file is larger than " +
                          std::to_string(kMaxCaseFileBytes >> 20) + " MiB; the limit is " +
                          std::to_string(kMaxCaseFileBytes >> 20) + " MiB");
  }
  if (in.bad()) throw CaseLoadError("cannot read '" + path + "'");
  return text;
}

v1::Case parse_case_text(const std::string& text) {
  google::protobuf::TextFormat::Parser parser;
  CollectErrors errors;
  parser.RecordErrorsTo(&errors);
  // Without a limit a deeply nested text recurses until the stack overflows.
  parser.SetRecursionLimit(kMaxTextNesting);
  v1::Case c;
  if (!parser.ParseFromString(text, &c)) {
    if (errors.too_deep) {
      const std::string why = describe_deep_nesting(text);
      throw CaseLoadError((why.empty() ? std::string() : why + " (") +
                          "the case text nests messages deeper than the parser's limit of " +
                          std::to_string(kMaxTextNesting) + ": " + errors.text +
                          (why.empty() ? "" : ")"));
    }
    throw CaseLoadError("malformed case text: " +
                        (errors.text.empty() ? std::string("parse error") : errors.text));
  }
  return c;
}

void inline_point_files(v1::Case& c, const std::string& base_dir) {
  // The walk below recurses over shapes: refuse a tree deeper than validation allows first.
  PointBudget budget;
  budget.dimension = c.dimension();
  auto region = [&](v1::Shape& s, const std::string& field) {
    const ShapeTreeSize n = measure_shape(s);
    if (n.depth > kMaxShapeDepth) throw CaseLoadError(field + ": " + shape_depth_error(n.depth));
    budget.used += n.points;
    budget.polygon_vertices += n.polygon_vertices;
    budget.mesh_triangles += n.mesh_triangles;
    budget.grid_nodes += n.grid_nodes;
  };
  for (int i = 0; i < c.fluids_size(); ++i)
    region(*c.mutable_fluids(i)->mutable_shape(), "fluids[" + std::to_string(i) + "].shape");
  for (int i = 0; i < c.walls_size(); ++i)
    region(*c.mutable_walls(i)->mutable_shape(), "walls[" + std::to_string(i) + "].shape");
  for (int i = 0; i < c.bodies_size(); ++i)
    region(*c.mutable_bodies(i)->mutable_shape(), "bodies[" + std::to_string(i) + "].shape");
  for (int i = 0; i < c.elastic_bodies_size(); ++i)
    region(*c.mutable_elastic_bodies(i)->mutable_shape(),
           "elastic_bodies[" + std::to_string(i) + "].shape");
  for (int i = 0; i < c.fluids_size(); ++i)
    inline_shape(*c.mutable_fluids(i)->mutable_shape(), base_dir,
                 "fluids[" + std::to_string(i) + "].shape", budget);
  for (int i = 0; i < c.walls_size(); ++i)
    inline_shape(*c.mutable_walls(i)->mutable_shape(), base_dir,
                 "walls[" + std::to_string(i) + "].shape", budget);
  for (int i = 0; i < c.bodies_size(); ++i)
    inline_shape(*c.mutable_bodies(i)->mutable_shape(), base_dir,
                 "bodies[" + std::to_string(i) + "].shape", budget);
  for (int i = 0; i < c.elastic_bodies_size(); ++i)
    inline_shape(*c.mutable_elastic_bodies(i)->mutable_shape(), base_dir,
                 "elastic_bodies[" + std::to_string(i) + "].shape", budget);
}

v1::Case load_case_file(const std::string& path) {
  v1::Case c = parse_case_text(read_text_file(path));
  const std::string dir = std::filesystem::path(path).parent_path().string();
  inline_point_files(c, dir);
  inline_reference_data(c, dir);
  return c;
}

std::string case_to_text(const v1::Case& c) {
  std::string out;
  google::protobuf::TextFormat::PrintToString(c, &out);
  return out;
}

}  // namespace sph
