#pragma once
// Why case text nests too deep to parse, for the message of the refusal: the text-format parser
// stops at kMaxTextNesting (case/case_limits.h) and reports only a line and column; this scan
// names the region whose shapes nest too deep and how deep they go. It walks the tokens with
// an explicit stack, so it is safe (and linear) on text of any depth.
#include <string>

namespace sph {

// "fluids[0].shape: shapes nest 4000 deep; the limit is 32" for the first top-level field of
// `text` whose shapes nest deeper than kMaxShapeDepth, or the first that nests deeper than
// kMaxTextNesting messages when that is not shapes; "" when neither is found.
std::string describe_deep_nesting(const std::string& text);

}  // namespace sph
