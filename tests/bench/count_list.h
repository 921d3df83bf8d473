// "1,8,64" as given to --threads= and --clients: the benchmarks' lists of
// counts. std::stoi throws std::invalid_argument on an item that is not one.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace acomms::bench {

inline std::vector<int> parse_count_list(const std::string& text) {
  std::vector<int> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) values.push_back(std::stoi(item));
  return values;
}

}  // namespace acomms::bench
