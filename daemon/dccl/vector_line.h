// One line of the conformance-vector format, also what `acommsctl dccl
// encode` reads:
//
//   |pkg.Type| <protobuf text format> => <hex>
//
// The " => hex" tail is optional. It is found outside string literals only:
// `s: "a => b"` is a string, not an arrow (text format has no other place
// where " => " can appear).
//
// Thread-safe: a pure function.
#pragma once

#include <string>
#include <string_view>

namespace acomms::dccl {

struct VectorLine {
  std::string type;  // "pkg.Type"
  std::string text;  // the text format between the type and the arrow
  std::string hex;   // after " => ", trimmed; empty when there is none
};

// Throws std::invalid_argument when the line does not start with |type|.
VectorLine parse_vector_line(std::string_view line);

}  // namespace acomms::dccl
