#include "defs_command.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "api_client.h"
#include "global_options.h"
#include "output.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

struct LoadOptions {
  std::vector<std::string> files;
  std::vector<std::string> include_dirs;
  bool send_inline = false;
};

struct ListOptions {
  std::vector<std::string> types;
  bool fields = false;
  bool names = false;
};

std::string range_text(uint64_t low, uint64_t high) {
  return low == high ? std::to_string(low) : std::to_string(low) + ".." + std::to_string(high);
}

void print_fields(const v1::TypeInfo& type) {
  for (const v1::FieldBudget& field : type.fields()) {
    // Paths are "pkg.Type.a.b"; the type is on the line above.
    std::string path = field.path();
    if (path.rfind(type.name() + ".", 0) == 0) path = path.substr(type.name().size() + 1);
    std::printf("    %-28s %-18s %-5s %s bits\n", path.c_str(), field.codec().c_str(),
                field.in_head() ? "head" : "body", range_text(field.min_bits(), field.max_bits()).c_str());
  }
}

void print_types(const google::protobuf::RepeatedPtrField<v1::TypeInfo>& types, bool with_fields) {
  std::printf("%-32s %6s  %-12s %s\n", "TYPE", "ID", "BYTES", "MAX_BYTES");
  for (const v1::TypeInfo& type : types) {
    std::string id = type.dccl_id() < 0 ? "omit" : std::to_string(type.dccl_id());
    // An authenticated type's trailer comes on top of its DCCL bytes.
    const std::string auth = type.auth_trailer_bits() == 0
                                 ? ""
                                 : "  (+" + std::to_string(type.auth_trailer_bits() / 8) + " bytes auth trailer)";
    std::printf("%-32s %6s  %-12s %u%s\n", type.name().c_str(), id.c_str(),
                range_text(type.min_bytes(), type.max_bytes()).c_str(), type.max_bytes_allowed(), auth.c_str());
    if (with_fields) print_fields(type);
  }
}

std::string read_local_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw UsageError("cannot read " + path + " (with --inline the files are read here, not by the daemon)");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

void run_load(const GlobalOptions& global, const LoadOptions& options) {
  v1::LoadDefinitionsRequest request;
  for (const std::string& file : options.files) {
    if (options.send_inline) {
      v1::InlineDefinition* definition = request.add_inline_();
      definition->set_name(std::filesystem::path(file).filename().string());
      definition->set_text(read_local_file(file));
    } else {
      request.add_paths(file);
    }
  }
  for (const std::string& dir : options.include_dirs) request.add_include_dirs(dir);
  ApiClient client(global);
  v1::LoadDefinitionsResponse response = client.call(&v1::Acomms::Stub::LoadDefinitions, request);
  if (global.json) {
    print_json(response);
    return;
  }
  print_types(response.types(), false);
}

void run_list(const GlobalOptions& global, const ListOptions& options) {
  v1::ListTypesRequest request;
  for (const std::string& type : options.types) request.add_types(type);
  request.set_fields(options.fields);
  ApiClient client(global);
  v1::ListTypesResponse response = client.call(&v1::Acomms::Stub::ListTypes, request);
  if (options.names) {
    for (const v1::TypeInfo& type : response.types()) std::cout << type.name() << "\n";
  } else if (global.json) {
    print_json(response);
  } else {
    print_types(response.types(), options.fields);
  }
}

void add_load(CLI::App* defs, const GlobalOptions& global) {
  static LoadOptions options;
  CLI::App* load = defs->add_subcommand("load", "Load DCCL message definitions (.proto files) into the daemon");
  load->add_option("FILE", options.files, "The .proto files: paths on the daemon's machine (see --inline)")
      ->required()
      ->type_name("");
  load->add_option("-I,--include", options.include_dirs, "Directory (on the daemon's machine) that imports resolve in")
      ->type_name("DIR")
      ->allow_extra_args(false);
  load->add_flag("--inline", options.send_inline,
                 "Read the files here and send their text (named by their basename), for a daemon on "
                 "another machine");
  load->footer(
      "The files are .proto files whose messages carry (dccl.msg) options. Each new type gets a queue; "
      "the definitions are kept and loaded again when the daemon restarts. Nothing is loaded if any "
      "file has a problem: every problem is listed as file:line:col.\n\n"
      "Examples:\n"
      "  acommsctl defs load /etc/acommsd/mission.proto -I /etc/acommsd\n"
      "  acommsctl --socket tcp:buoy:50051 defs load --inline ./mission.proto");
  load->callback([&global] { run_load(global, options); });
}

void add_list(CLI::App* defs, const GlobalOptions& global) {
  static ListOptions options;
  CLI::App* list = defs->add_subcommand("list", "List the loaded DCCL types, their ids and encoded sizes");
  list->add_option("TYPE", options.types, "Only these types (default: all)")->type_name("");
  list->add_flag("--fields", options.fields, "Show each field's codec, head/body and bits");
  // For shell completion: names only, one per line.
  list->add_flag("--names", options.names, "Print type names only")->group("");
  list->footer(
      "Columns: type, DCCL id, encoded size in bytes (min..max), the (dccl.msg).max_bytes limit. --fields "
      "adds each field's codec, head or body, and bits: where a frame's bytes go.\n\n"
      "Examples:\n"
      "  acommsctl defs list\n"
      "  acommsctl defs list gv.NavigationReport --fields");
  list->callback([&global] { run_list(global, options); });
}

}  // namespace

void add_defs_command(CLI::App& app, const GlobalOptions& options) {
  CLI::App* defs = app.add_subcommand("defs", "Load and list the DCCL message definitions the daemon uses");
  defs->require_subcommand(1);
  defs->footer("Example:\n  acommsctl defs load /etc/acommsd/mission.proto && acommsctl defs list --fields");
  add_load(defs, options);
  add_list(defs, options);
}

}  // namespace acomms::cli
