#pragma once
// A fleet file (acomms/v1/fleet.proto) loaded with its includes, and each
// node's config resolved from its ancestors (README "Fleet configuration").
//
// The decision: every entry keeps its own settings and where each field was
// written (core/fleet_merge.h); a node is resolved on demand by merging its
// ancestors' own settings in order (each ancestor once, parents' parents
// first), so a class included through two parents is not applied twice.
// Paths in a config (dccl.proto_files, data_dir, the keyring, ...) are
// relative to the file that names them, made absolute at load, so a fleet
// runs the same from any directory.
//
// Thread-safe: a loaded Fleet is immutable; load() and resolve() share
// nothing between calls.

#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "acomms/v1/fleet.pb.h"
#include "core/fleet_merge.h"

namespace acomms::core {

struct FleetEntry {
  std::string name;
  Origin where;  // the `name:` line
  std::vector<std::string> parents;
  std::vector<Origin> parent_where;
  bool abstract = false;
  v1::Config config;
  Provenance config_where;
  v1::FleetKeys keys;
  Provenance keys_where;
};

// One node's settings, merged.
struct ResolvedNode {
  std::string name;
  Origin where;
  std::vector<std::string> lineage;  // the ancestors merged, in order, then the node
  v1::Config config;
  Provenance config_where;
  v1::FleetKeys keys;
  Provenance keys_where;
};

class Fleet {
 public:
  // Reads `path` and its includes. Throws ConfigError (file, line, what).
  static Fleet load(const std::string& path);
  // The same from text already read (includes relative to `path`'s folder).
  static Fleet parse(const std::string& text, const std::string& path);

  const std::string& path() const { return path_; }
  const std::vector<FleetEntry>& entries() const { return entries_; }
  const FleetEntry* find(const std::string& name) const;
  // The entries that are nodes (not abstract), in the order they were read.
  std::vector<std::string> node_names() const;
  // Throws ConfigError for an unknown name, a missing parent or a cycle.
  ResolvedNode resolve(const std::string& name) const;

 private:
  // Reads `path` (its `text` when given) after its includes; a file already
  // read is skipped, which also ends include cycles.
  void read(const std::string& path, const std::string* text);
  void lineage(const std::string& name, std::vector<std::string>& order, std::vector<std::string>& stack) const;

  std::string path_;
  std::vector<FleetEntry> entries_;
  std::vector<std::string> files_read_;  // canonical paths
};

// The config acommsd runs for node `name` of `fleet`: resolved, validated
// and defaulted as a single config file is (config_loader.h); errors name
// the fleet file and line the offending field came from. Throws
// ConfigError (also for a class).
v1::Config node_config(const Fleet& fleet, const std::string& name);

// The same for the fleet at `path`: resolved,
// validated and defaulted as a single config file is (config_loader.h);
// errors name the fleet file and line the offending field came from.
// Throws ConfigError.
v1::Config load_fleet_node_config(const std::string& path, const std::string& name);

}  // namespace acomms::core
