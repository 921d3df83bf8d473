#include "tile_source.h"

#include <sqlite3.h>

#include <stdexcept>

namespace acomms::cli::geov {

MbTiles::MbTiles(const std::string& path) {
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_FULLMUTEX, nullptr) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw std::runtime_error("--mbtiles " + path + ": " + why);
  }
  sqlite3_stmt* stmt = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT count(*) FROM tiles", -1, &stmt, nullptr) != SQLITE_OK ||
      sqlite3_step(stmt) != SQLITE_ROW) {
    const std::string why = sqlite3_errmsg(db_);
    sqlite3_finalize(stmt);
    sqlite3_close(db_);
    throw std::runtime_error("--mbtiles " + path + ": not an MBTiles file (no table tiles: " + why + ")");
  }
  sqlite3_finalize(stmt);
  if (sqlite3_prepare_v2(db_, "SELECT value FROM metadata WHERE name = 'format'", -1, &stmt, nullptr) == SQLITE_OK &&
      sqlite3_step(stmt) == SQLITE_ROW) {
    const std::string format = reinterpret_cast<const char*>(sqlite3_column_text(stmt, 0));
    if (format == "jpg" || format == "jpeg") content_type_ = "image/jpeg";
    if (format == "webp") content_type_ = "image/webp";
  }
  sqlite3_finalize(stmt);
}

MbTiles::~MbTiles() { sqlite3_close(db_); }

std::optional<std::string> MbTiles::tile(int z, int64_t x, int64_t y) const {
  if (z < 0 || z > 30 || x < 0 || y < 0 || x >= (int64_t{1} << z) || y >= (int64_t{1} << z)) return std::nullopt;
  sqlite3_stmt* stmt = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT tile_data FROM tiles WHERE zoom_level = ? AND tile_column = ? AND tile_row = ?",
                         -1, &stmt, nullptr) != SQLITE_OK) {
    return std::nullopt;
  }
  sqlite3_bind_int(stmt, 1, z);
  sqlite3_bind_int64(stmt, 2, x);
  sqlite3_bind_int64(stmt, 3, (int64_t{1} << z) - 1 - y);  // MBTiles rows count from the south
  std::optional<std::string> out;
  if (sqlite3_step(stmt) == SQLITE_ROW) {
    const void* data = sqlite3_column_blob(stmt, 0);
    out = std::string(static_cast<const char*>(data), static_cast<std::size_t>(sqlite3_column_bytes(stmt, 0)));
  }
  sqlite3_finalize(stmt);
  return out;
}

}  // namespace acomms::cli::geov
