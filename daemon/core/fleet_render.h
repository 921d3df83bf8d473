#pragma once
// A resolved fleet node's config as protobuf text format, one field a line,
// optionally with "# file:line" after each field (`acommsctl fleet render
// --explain`), and which field each line holds, so that an error found in
// the text can be traced back to the fleet file.
//
// Thread-safe: a function of its arguments.

#include <string>
#include <vector>

#include <google/protobuf/message.h>

#include "core/fleet_merge.h"

namespace acomms::core {

struct RenderedText {
  std::string text;
  std::vector<std::string> line_paths;  // line_paths[i]: the field on line i + 1 ("" for "}")
};

// `where` may be null (no comments).
RenderedText render_located(const google::protobuf::Message& message, const Provenance* where);

}  // namespace acomms::core
