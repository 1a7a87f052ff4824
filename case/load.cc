#include "case/load.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "case/reference_data.h"

namespace sph {
namespace {

class CollectErrors : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, google::protobuf::io::ColumnNumber column,
                const std::string& message) override {
    if (!text.empty()) text += "; ";
    text += "line " + std::to_string(line + 1) + ", column " + std::to_string(column + 1) + ": " +
            message;
  }
  std::string text;
};

std::vector<v1::Vec3> read_point_file(const std::string& path, const std::string& field) {
  std::ifstream in(path);
  if (!in) throw CaseLoadError(field + ": cannot read point file '" + path + "'");
  std::vector<v1::Vec3> points;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    double xyz[3] = {0, 0, 0};
    int n = 0;
    while (n < 3 && ls >> xyz[n]) ++n;
    if (n == 0 && ls.eof()) continue;
    std::string rest;
    if (n < 2 || (ls >> rest))
      throw CaseLoadError(field + ": " + path + ":" + std::to_string(lineno) +
                          ": expected 'x y' or 'x y z'");
    v1::Vec3 p;
    p.set_x(xyz[0]);
    p.set_y(xyz[1]);
    p.set_z(xyz[2]);
    points.push_back(p);
  }
  return points;
}

void inline_shape(v1::Shape& s, const std::string& base, const std::string& field) {
  switch (s.kind_case()) {
    case v1::Shape::kPoints: {
      auto* ps = s.mutable_points();
      if (!ps->file().empty()) {
        std::filesystem::path p(ps->file());
        if (p.is_relative()) p = std::filesystem::path(base) / p;
        for (auto& v : read_point_file(p.string(), field + ".points.file")) *ps->add_points() = v;
        ps->clear_file();
      }
      break;
    }
    case v1::Shape::kUnion:
      for (int i = 0; i < s.union_().shapes_size(); ++i)
        inline_shape(*s.mutable_union_()->mutable_shapes(i), base,
                     field + ".union.shapes[" + std::to_string(i) + "]");
      break;
    case v1::Shape::kIntersection:
      for (int i = 0; i < s.intersection().shapes_size(); ++i)
        inline_shape(*s.mutable_intersection()->mutable_shapes(i), base,
                     field + ".intersection.shapes[" + std::to_string(i) + "]");
      break;
    case v1::Shape::kDifference:
      inline_shape(*s.mutable_difference()->mutable_base(), base, field + ".difference.base");
      for (int i = 0; i < s.difference().subtract_size(); ++i)
        inline_shape(*s.mutable_difference()->mutable_subtract(i), base,
                     field + ".difference.subtract[" + std::to_string(i) + "]");
      break;
    case v1::Shape::kShell:
      inline_shape(*s.mutable_shell()->mutable_inner(), base, field + ".shell.inner");
      break;
    default:
      break;
  }
}

}  // namespace

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseLoadError("cannot read '" + path + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

v1::Case parse_case_text(const std::string& text) {
  google::protobuf::TextFormat::Parser parser;
  CollectErrors errors;
  parser.RecordErrorsTo(&errors);
  v1::Case c;
  if (!parser.ParseFromString(text, &c)) {
    throw CaseLoadError("malformed case text: " +
                        (errors.text.empty() ? std::string("parse error") : errors.text));
  }
  return c;
}

void inline_point_files(v1::Case& c, const std::string& base_dir) {
  for (int i = 0; i < c.fluids_size(); ++i)
    inline_shape(*c.mutable_fluids(i)->mutable_shape(), base_dir,
                 "fluids[" + std::to_string(i) + "].shape");
  for (int i = 0; i < c.walls_size(); ++i)
    inline_shape(*c.mutable_walls(i)->mutable_shape(), base_dir,
                 "walls[" + std::to_string(i) + "].shape");
  for (int i = 0; i < c.bodies_size(); ++i)
    inline_shape(*c.mutable_bodies(i)->mutable_shape(), base_dir,
                 "bodies[" + std::to_string(i) + "].shape");
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
