#pragma once
// The map page's files, built into acommsctl at build time (cli/CMakeLists
// .txt embeds Debian's libjs-leaflet and cli/geov/assets/): a ship without
// internet, or a machine without libjs-leaflet installed, still gets the
// whole page. Served by name only; no request reaches the file system.
//
// Thread-safety: immutable after first use (a function-local static).

#include <string_view>
#include <vector>

namespace acomms::cli::geov {

struct EmbeddedFile {
  std::string_view name;  // the URL path: "/", "/leaflet.js"
  std::string_view type;  // Content-Type (text/* are UTF-8)
  std::string_view bytes;
};

const std::vector<EmbeddedFile>& embedded_assets();

// The asset served at `path`, or nullptr.
const EmbeddedFile* find_asset(std::string_view path);

}  // namespace acomms::cli::geov
