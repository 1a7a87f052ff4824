#include "case/text_nesting.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>

#include <algorithm>
#include <map>
#include <vector>

#include "case/case_bounds.h"
#include "case/case_limits.h"

namespace sph {
namespace {

namespace io = google::protobuf::io;

class IgnoreErrors : public io::ErrorCollector {
 public:
  void AddError(int, io::ColumnNumber, const std::string&) override {}
};

// One open `{` (a message) or `[` (a list of values or messages) of the text.
struct Open {
  std::string name;     // the field it belongs to
  bool list = false;    // `[`: its `{` elements belong to `name` too
  int shape_depth = 0;  // shapes nested down to here (0 outside shapes)
};

// Whether field `name` inside a message of field `parent` holds a Shape (case.proto).
bool is_shape_field(const std::string& parent, const std::string& name, int depth) {
  if (depth == 1) return name == "shape";  // fluids { shape { ... } } and walls, bodies
  if (parent == "union" || parent == "intersection") return name == "shapes";
  if (parent == "difference") return name == "base" || name == "subtract";
  if (parent == "shell") return name == "inner";
  return false;
}

}  // namespace

std::string describe_deep_nesting(const std::string& text) {
  io::ArrayInputStream input(text.data(), static_cast<int>(text.size()));
  IgnoreErrors ignore;
  io::Tokenizer tokens(&input, &ignore);
  tokens.set_comment_style(io::Tokenizer::SH_COMMENT_STYLE);

  std::vector<Open> stack;
  int messages = 0;                  // open `{` on the stack
  std::map<std::string, int> count;  // elements of each top-level field so far
  std::string last_identifier, top_field, deep_field;
  int region_max_shapes = 0, region_max_messages = 0;

  auto finish_region = [&]() -> std::string {
    if (region_max_shapes > kMaxShapeDepth)
      return deep_field + ": " + shape_depth_error(region_max_shapes);
    if (region_max_messages > kMaxTextNesting)
      return deep_field + ": the text nests " + std::to_string(region_max_messages) +
             " messages deep; the limit is " + std::to_string(kMaxTextNesting);
    return "";
  };

  while (tokens.Next()) {
    const auto& t = tokens.current();
    if (t.type == io::Tokenizer::TYPE_IDENTIFIER) {
      last_identifier = t.text;
      continue;
    }
    if (t.type != io::Tokenizer::TYPE_SYMBOL) continue;
    const char s = t.text[0];
    if (s == '[') {
      stack.push_back({last_identifier, true, stack.empty() ? 0 : stack.back().shape_depth});
    } else if (s == ']') {
      if (!stack.empty() && stack.back().list) stack.pop_back();
    } else if (s == '{' || s == '<') {
      const bool in_list = !stack.empty() && stack.back().list;
      const std::string name = in_list ? stack.back().name : last_identifier;
      const int depth = messages + 1;
      if (depth == 1) {
        top_field = name + "[" + std::to_string(count[name]++) + "]";
        region_max_shapes = region_max_messages = 0;
        deep_field.clear();
      }
      // The field of the message that holds this one (a list is not a message).
      std::string parent;
      for (auto it = stack.rbegin(); it != stack.rend(); ++it)
        if (!it->list) {
          parent = it->name;
          break;
        }
      const int outer = stack.empty() ? 0 : stack.back().shape_depth;
      const bool shape = is_shape_field(parent, name, depth - 1);
      stack.push_back({name, false, shape ? outer + 1 : outer});
      ++messages;
      if (depth == 2) deep_field = top_field + "." + name;
      region_max_shapes = std::max(region_max_shapes, stack.back().shape_depth);
      region_max_messages = std::max(region_max_messages, depth);
    } else if (s == '}' || s == '>') {
      while (!stack.empty() && stack.back().list) stack.pop_back();  // an unclosed list
      if (stack.empty()) continue;
      stack.pop_back();
      --messages;
      if (messages == 0) {
        if (auto found = finish_region(); !found.empty()) return found;
      }
    }
  }
  return finish_region();  // text that ends inside a region
}

}  // namespace sph
