#pragma once
// Comma-separated lists on the command line ("1,2,3" for repeated fields,
// "3-6,8" for simulated network sizes).

#include <string>
#include <vector>

namespace acomms::cli {

// "a,b,,c" -> "a", "b", "", "c"; "" -> one empty token. Empty tokens are the
// caller's to refuse or skip.
std::vector<std::string> split_commas(const std::string& text);

}  // namespace acomms::cli
