#include "core/fleet.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "core/config_error.h"
#include "core/first_parse_error.h"
#include "core/config_loader.h"
#include "core/fleet_render.h"

namespace acomms::core {

namespace {

namespace pb = google::protobuf;
namespace fs = std::filesystem;

// Fields that hold a path: relative ones are relative to the fleet file
// that names them.
bool is_path_field(const pb::FieldDescriptor* field) {
  static const std::set<std::string> paths = {
      "acomms.v1.Config.data_dir",         "acomms.v1.GrpcConfig.unix_socket",
      "acomms.v1.TlsConfig.cert_file",     "acomms.v1.TlsConfig.key_file",
      "acomms.v1.TlsConfig.client_ca_file", "acomms.v1.DcclConfig.proto_files",
      "acomms.v1.DcclConfig.include_dirs", "acomms.v1.DcclConfig.passphrase_file",
      "acomms.v1.AuthConfig.keyring_file", "acomms.drivers.SimPhysicsConfig.env_file",
  };
  return paths.count(std::string(field->full_name())) > 0;
}

std::string anchored(const fs::path& dir, const std::string& value) {
  if (value.empty() || fs::path(value).is_absolute()) return value;
  return (dir / value).lexically_normal().string();
}

void anchor_paths(pb::Message& message, const fs::path& dir) {
  const pb::Reflection* reflection = message.GetReflection();
  std::vector<const pb::FieldDescriptor*> fields;
  reflection->ListFields(message, &fields);
  for (const pb::FieldDescriptor* field : fields) {
    if (field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      if (!field->is_repeated()) {
        anchor_paths(*reflection->MutableMessage(&message, field), dir);
        continue;
      }
      for (int i = 0; i < reflection->FieldSize(message, field); ++i) {
        anchor_paths(*reflection->MutableRepeatedMessage(&message, field, i), dir);
      }
    } else if (is_path_field(field)) {
      if (!field->is_repeated()) {
        reflection->SetString(&message, field, anchored(dir, reflection->GetString(message, field)));
        continue;
      }
      for (int i = 0; i < reflection->FieldSize(message, field); ++i) {
        reflection->SetRepeatedString(&message, field, i,
                                      anchored(dir, reflection->GetRepeatedString(message, field, i)));
      }
    }
  }
}

std::string read_file(const std::string& path, const std::string& included_from, const Origin& where) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (included_from.empty()) throw ConfigError(path, 0, 0, "", "cannot open fleet file");
    throw ConfigError(where.file, where.line, 0, "include", "cannot open included file " + path);
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Fleet Fleet::load(const std::string& path) {
  Fleet fleet;
  fleet.path_ = path;
  fleet.read(path, nullptr);
  return fleet;
}

Fleet Fleet::parse(const std::string& text, const std::string& path) {
  Fleet fleet;
  fleet.path_ = path;
  fleet.read(path, &text);
  return fleet;
}

void Fleet::read(const std::string& path, const std::string* given_text) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(path, ec);
  std::string key = ec ? path : canonical.string();
  if (std::find(files_read_.begin(), files_read_.end(), key) != files_read_.end()) return;  // read once
  files_read_.push_back(key);
  const std::string text = given_text != nullptr ? *given_text : read_file(path, "", {});

  v1::FleetFile file;
  pb::TextFormat::Parser parser;
  FirstParseError errors;
  pb::TextFormat::ParseInfoTree tree;
  parser.RecordErrorsTo(&errors);
  parser.WriteLocationsTo(&tree);
  if (!parser.ParseFromString(text, &file)) {
    const auto& e = errors.error();
    if (!e) throw ConfigError(path, 0, 0, "", "not a fleet file");
    throw ConfigError(path, e->line + 1, e->column + 1, "", e->message);
  }
  const fs::path dir = fs::absolute(fs::path(path)).parent_path();
  const pb::Descriptor* file_type = v1::FleetFile::descriptor();
  for (int i = 0; i < file.include_size(); ++i) {
    Origin where{path, tree.GetLocation(file_type->FindFieldByName("include"), i).line + 1};
    std::string included = (fs::path(path).parent_path() / file.include(i)).lexically_normal().string();
    if (fs::path(file.include(i)).is_absolute()) included = file.include(i);
    std::string text_of_include = read_file(included, path, where);
    read(included, &text_of_include);
  }
  static const std::regex name_pattern("[A-Za-z0-9_-]+");
  const pb::Descriptor* node_type = v1::FleetNode::descriptor();
  for (int i = 0; i < file.node_size(); ++i) {
    v1::FleetNode& node = *file.mutable_node(i);
    const pb::TextFormat::ParseInfoTree* node_tree = tree.GetTreeForNested(file_type->FindFieldByName("node"), i);
    pb::TextFormat::ParseInfoTree no_places;
    if (node_tree == nullptr) node_tree = &no_places;  // every parsed node has one; never trust that blindly
    FleetEntry entry;
    entry.name = node.name();
    int node_line = tree.GetLocation(file_type->FindFieldByName("node"), i).line + 1;
    int name_line = node_tree->GetLocation(node_type->FindFieldByName("name"), -1).line + 1;
    entry.where = Origin{path, name_line > 0 ? name_line : node_line};
    if (!std::regex_match(entry.name, name_pattern)) {
      throw ConfigError(path, entry.where.line, 0, "node.name",
                        "\"" + entry.name + "\" is not a node name (letters, digits, '_', '-')");
    }
    if (const FleetEntry* before = find(entry.name)) {
      throw ConfigError(path, entry.where.line, 0, "node.name",
                        "\"" + entry.name + "\" is already defined at " + to_string(before->where));
    }
    for (int p = 0; p < node.parent_size(); ++p) {
      entry.parents.push_back(node.parent(p));
      entry.parent_where.push_back(
          Origin{path, node_tree->GetLocation(node_type->FindFieldByName("parent"), p).line + 1});
    }
    entry.abstract = node.abstract();
    anchor_paths(*node.mutable_config(), dir);
    entry.config = node.config();
    entry.keys = node.keys();
    if (auto* t = node_tree->GetTreeForNested(node_type->FindFieldByName("config"), -1)) {
      record_provenance(entry.config, *t, path, entry.config_where);
    }
    if (auto* t = node_tree->GetTreeForNested(node_type->FindFieldByName("keys"), -1)) {
      record_provenance(entry.keys, *t, path, entry.keys_where);
    }
    entries_.push_back(std::move(entry));
  }
}

const FleetEntry* Fleet::find(const std::string& name) const {
  for (const FleetEntry& entry : entries_) {
    if (entry.name == name) return &entry;
  }
  return nullptr;
}

std::vector<std::string> Fleet::node_names() const {
  std::vector<std::string> names;
  for (const FleetEntry& entry : entries_) {
    if (!entry.abstract) names.push_back(entry.name);
  }
  return names;
}

void Fleet::lineage(const std::string& name, std::vector<std::string>& order, std::vector<std::string>& stack) const {
  if (std::find(order.begin(), order.end(), name) != order.end()) return;
  const FleetEntry* entry = find(name);
  stack.push_back(name);
  for (size_t p = 0; p < entry->parents.size(); ++p) {
    const std::string& parent = entry->parents[p];
    const Origin& where = entry->parent_where[p];
    if (find(parent) == nullptr) throw ConfigError(where.file, where.line, 0, "parent", "no node or class \"" + parent + "\"");
    if (std::find(stack.begin(), stack.end(), parent) != stack.end()) {
      throw ConfigError(where.file, where.line, 0, "parent", "\"" + parent + "\" is its own ancestor (a cycle)");
    }
    lineage(parent, order, stack);
  }
  stack.pop_back();
  order.push_back(name);
}

ResolvedNode Fleet::resolve(const std::string& name) const {
  const FleetEntry* entry = find(name);
  if (entry == nullptr) throw ConfigError(path_, 0, 0, "", "no node \"" + name + "\" in the fleet");
  ResolvedNode node;
  node.name = name;
  node.where = entry->where;
  std::vector<std::string> stack;
  lineage(name, node.lineage, stack);
  for (const std::string& level : node.lineage) {
    const FleetEntry& own = *find(level);
    merge_located(own.config, own.config_where, node.config, node.config_where);
    merge_located(own.keys, own.keys_where, node.keys, node.keys_where);
  }
  return node;
}

v1::Config load_fleet_node_config(const std::string& path, const std::string& name) {
  return node_config(Fleet::load(path), name);
}

v1::Config node_config(const Fleet& fleet, const std::string& name) {
  const std::string& path = fleet.path();
  const FleetEntry* entry = fleet.find(name);
  if (entry != nullptr && entry->abstract) {
    throw ConfigError(entry->where.file, entry->where.line, 0, "abstract", "\"" + name + "\" is a class, not a node");
  }
  ResolvedNode node = fleet.resolve(name);
  RenderedText rendered = render_located(node.config, nullptr);
  try {
    return parse_config(rendered.text, path + " (node " + name + ")");
  } catch (const ConfigError& e) {
    // The error's line is in the rendered text: name the fleet line the
    // field came from instead.
    if (e.line() < 1 || e.line() > static_cast<int>(rendered.line_paths.size())) throw;
    auto it = node.config_where.find(rendered.line_paths[e.line() - 1]);
    if (it == node.config_where.end()) throw;
    throw ConfigError(it->second.file, it->second.line, 0, e.field(), e.problem() + " (node " + name + ")");
  }
}

}  // namespace acomms::core
