#pragma once
// Map tiles under the tracks, when the operator has some: a local MBTiles
// file (an SQLite database of tiles, the MBTiles 1.3 specification: table
// `tiles` with zoom_level, tile_column, tile_row counted from the south, as
// in TMS) served at /tiles/{z}/{x}/{y}, or a tile URL the page loads itself.
// Without either the page draws a metric grid and needs nothing from
// anywhere.
//
// Thread-safety: MbTiles::tile may be called from any thread (the database
// is opened read-only with SQLite's serialized mode; one statement per call).

#include <cstdint>
#include <optional>
#include <string>

struct sqlite3;

namespace acomms::cli::geov {

class MbTiles {
 public:
  // Opens `path` read-only; throws std::runtime_error naming it when it is
  // not an MBTiles file.
  explicit MbTiles(const std::string& path);
  ~MbTiles();
  MbTiles(const MbTiles&) = delete;
  MbTiles& operator=(const MbTiles&) = delete;

  // The tile at zoom z, column x, row y counted from the north (as Leaflet
  // asks), or nullopt.
  std::optional<std::string> tile(int z, int64_t x, int64_t y) const;
  // "image/png", "image/jpeg" or "image/webp", from the metadata's format.
  const std::string& content_type() const { return content_type_; }

 private:
  sqlite3* db_ = nullptr;
  std::string content_type_ = "image/png";
};

}  // namespace acomms::cli::geov
