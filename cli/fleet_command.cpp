#include "fleet_command.h"

#include <google/protobuf/text_format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/config_error.h"
#include "core/fleet.h"
#include "core/fleet_import.h"
#include "core/fleet_render.h"
#include "core/node_links.h"
#include "eval/fleet_check.h"

namespace acomms::cli {

namespace {

struct FleetOptions {
  std::string fleet;
  std::string node;
  bool explain = false;
  std::vector<std::string> files;
};

void run_ls(const FleetOptions& options) {
  core::Fleet fleet = core::Fleet::load(options.fleet);
  std::printf("%-16s %-8s %s\n", "NODE", "MODEM_ID", "FROM (ancestors, in merge order)");
  for (const std::string& name : fleet.node_names()) {
    core::ResolvedNode node = fleet.resolve(name);
    std::string lineage;
    for (size_t i = 0; i + 1 < node.lineage.size(); ++i) lineage += (lineage.empty() ? "" : " > ") + node.lineage[i];
    std::string id;
    try {
      id = std::to_string(core::node_id(node.config));
    } catch (const std::exception&) {
      id = "?";
    }
    std::printf("%-16s %-8s %s\n", name.c_str(), id.c_str(), lineage.c_str());
  }
}

void run_render(const FleetOptions& options) {
  core::Fleet fleet = core::Fleet::load(options.fleet);
  const core::FleetEntry* entry = fleet.find(options.node);
  if (entry != nullptr && entry->abstract) {
    throw core::ConfigError(entry->where.file, entry->where.line, 0, "abstract",
                            "\"" + options.node + "\" is a class, not a node");
  }
  core::ResolvedNode node = fleet.resolve(options.node);
  if (options.explain) {
    std::string lineage;
    for (const std::string& level : node.lineage) lineage += (lineage.empty() ? "" : " > ") + level;
    std::cout << "# node " << node.name << " (" << core::to_string(node.where) << "): " << lineage << "\n";
  }
  std::cout << core::render_located(node.config, options.explain ? &node.config_where : nullptr).text;
}

void run_check(const FleetOptions& options) {
  core::Fleet fleet = core::Fleet::load(options.fleet);
  std::vector<eval::FleetFinding> findings = eval::check_fleet(fleet);
  for (const eval::FleetFinding& finding : findings) std::cout << eval::to_string(finding) << "\n";
  const size_t nodes = fleet.node_names().size();
  if (findings.empty()) {
    std::cout << options.fleet << ": " << nodes << " nodes, no findings: may launch\n";
    return;
  }
  std::cout << options.fleet << ": " << nodes << " nodes, " << findings.size() << " finding"
            << (findings.size() == 1 ? "" : "s") << ": do not launch\n";
  std::cout.flush();
  throw CLI::RuntimeError(1);
}

void run_import(const FleetOptions& options) {
  std::vector<std::pair<std::string, v1::Config>> nodes;
  for (const std::string& file : options.files) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw core::ConfigError(file, 0, 0, "", "cannot open config file");
    std::ostringstream text;
    text << in.rdbuf();
    v1::Config config;
    // As written, not defaulted: the fleet keeps what the files say.
    if (!google::protobuf::TextFormat::ParseFromString(text.str(), &config)) {
      throw core::ConfigError(file, 0, 0, "", "not a valid config (acommsd --check-config " + file + " says where)");
    }
    nodes.emplace_back(std::filesystem::path(file).stem().string(), std::move(config));
  }
  v1::FleetFile fleet = core::import_fleet(nodes);
  std::cout << "# Made by `acommsctl fleet import`: \"common\" holds what every config agreed on.\n"
            << core::render_located(fleet, nullptr).text;
}

constexpr const char* kLsExample = "acommsctl fleet ls examples/fleet/fleet.conf";
constexpr const char* kRenderExample = "acommsctl fleet render auv_1 -f examples/fleet/fleet.conf --explain";
constexpr const char* kCheckExample = "acommsctl fleet check examples/fleet/fleet.conf";
constexpr const char* kImportExample = "acommsctl fleet import vehicle.conf topside.conf > fleet.conf";

}  // namespace

void add_fleet_command(CLI::App& app, const GlobalOptions&) {
  static FleetOptions options;
  CLI::App* fleet = app.add_subcommand(
      "fleet", "A fleet file (one config for every node, in levels): list, render, check, import (no daemon needed)");
  fleet->require_subcommand(1);
  fleet->footer(std::string("Examples:\n  ") + kLsExample + "\n  " + kRenderExample + "\n  " + kCheckExample + "\n  " +
                kImportExample);

  CLI::App* ls = fleet->add_subcommand("ls", "List the fleet's nodes: modem id and the levels each inherits");
  ls->add_option("FLEET", options.fleet, "Fleet file")->required();
  ls->footer(std::string("Example:\n  ") + kLsExample);
  ls->callback([] { run_ls(options); });

  CLI::App* render = fleet->add_subcommand(
      "render", "Print a node's complete config, flattened (what `acommsd --fleet F --node NAME` runs, before defaults)");
  render->add_option("NAME", options.node, "Node name")->required();
  render->add_option("-f,--fleet", options.fleet, "Fleet file (default: $ACOMMS_FLEET)")
      ->envname("ACOMMS_FLEET")
      ->required()
      ->type_name("FILE");
  render->add_flag("--explain", options.explain, "Add `# file:line` after each field: where its value came from");
  render->footer(std::string("Example:\n  ") + kRenderExample);
  render->callback([] { run_render(options); });

  CLI::App* check = fleet->add_subcommand(
      "check",
      "Find what would fail at sea: a DCCL id bound to two types or two versions of one, MAC cycles that differ on "
      "a link, slots for no node, a modem id twice, routes to nobody or in a loop, keys a receiver lacks, slots too "
      "short for their rate. Exit 0: may launch; 1: findings (each names both places, file:line)");
  check->add_option("FLEET", options.fleet, "Fleet file")->required();
  check->footer(std::string("Example:\n  ") + kCheckExample);
  check->callback([] { run_check(options); });

  CLI::App* import = fleet->add_subcommand(
      "import", "Print a first fleet file made from per-node config files: what they share in a class \"common\", "
                "each node (named after its file) with the rest");
  import->add_option("FILE", options.files, "Per-node config files")->required();
  import->footer(std::string("Example:\n  ") + kImportExample);
  import->callback([] { run_import(options); });
}

}  // namespace acomms::cli
