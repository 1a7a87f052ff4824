#pragma once
// Reading a case from .textproto text or file. Point files referenced by PointSet.file are
// read and inlined here, so the returned case stands alone (it is what gets submitted).
#include <stdexcept>
#include <string>

#include "sph/v1/case.pb.h"

namespace sph {

// Thrown for text that does not parse or a point file that cannot be read; what() names the
// line and column or the field path.
class CaseLoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses textproto text. Unknown fields and malformed values are errors, and so is text that
// nests messages deeper than kMaxTextNesting (case/case_limits.h): the message then names the
// region whose shapes nest too deep ("fluids[0].shape: shapes nest 4000 deep; the limit is
// 32"). Nothing recurses deeper than that limit.
v1::Case parse_case_text(const std::string& text);

// Replaces every PointSet.file (relative to base_dir) by its points, refusing a shape tree
// deeper than kMaxShapeDepth and files beyond kMaxPointsPerFile or the case's
// kMaxPointsPerCase (counted while reading).
void inline_point_files(v1::Case& c, const std::string& base_dir);

// parse_case_text + inline_point_files and inline_reference_data (case/reference_data.h)
// relative to the file's directory.
v1::Case load_case_file(const std::string& path);

// The canonical text form of a case (what is stored and written into result metadata).
std::string case_to_text(const v1::Case& c);

// The whole file; CaseLoadError past kMaxCaseFileBytes (read no further).
std::string read_text_file(const std::string& path);

}  // namespace sph
