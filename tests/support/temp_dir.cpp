#include "temp_dir.h"

#include <unistd.h>

#include <atomic>
#include <system_error>

namespace acomms::testing {

TempDir::TempDir(std::string_view prefix, const std::filesystem::path& base) {
  static std::atomic<int> counter{0};
  path_ = base / (std::string(prefix) + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;  // a destructor must not throw; a leftover is only litter
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace acomms::testing
