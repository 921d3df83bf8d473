#pragma once
// The few JSON pieces the map server writes by hand: numbers (non-finite as
// null, so the page never receives invalid JSON) and escaped strings.
//
// Thread-safety: pure functions.

#include <string>
#include <string_view>

namespace acomms::cli::geov {

std::string json_number(double value);
std::string json_string(std::string_view text);
// The same text escaped for XML character data and attribute values.
std::string xml_text(std::string_view text);

}  // namespace acomms::cli::geov
