#include "comma_list.h"

namespace acomms::cli {

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> tokens;
  size_t begin = 0;
  while (begin <= text.size()) {
    size_t end = text.find(',', begin);
    if (end == std::string::npos) end = text.size();
    tokens.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return tokens;
}

}  // namespace acomms::cli
