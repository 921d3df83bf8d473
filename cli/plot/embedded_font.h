#pragma once
// DejaVu Sans (fonts-dejavu-core), built into acommsctl at build time so its
// pictures have text without the font installed where it runs.
//
// Thread-safety: immutable after first use (a function-local static).

#include <string_view>
#include <vector>

namespace acomms::cli::plot {

struct EmbeddedFile {
  std::string_view name;
  std::string_view type;
  std::string_view bytes;
};

const std::vector<EmbeddedFile>& embedded_fonts();

}  // namespace acomms::cli::plot
