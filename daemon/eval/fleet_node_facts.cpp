#include "eval/fleet_node_facts.h"

#include <google/protobuf/descriptor.pb.h>

#include <set>

#include "core/config_error.h"
#include "core/fleet_render.h"
#include "core/node_links.h"
#include "dccl/codec.h"
#include "dccl/error.h"
#include "dccl/plugin_codecs.h"
#include "dccl/type_info.h"

namespace acomms::eval {

namespace {

namespace pb = google::protobuf;

void describe(const pb::Descriptor* type, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(std::string(type->full_name())).second) return;
  pb::DescriptorProto proto;
  type->CopyTo(&proto);
  proto.clear_name();  // nested types are compared by their layout and options
  out += std::string(type->full_name()) + ":" + proto.SerializeAsString();
  for (int i = 0; i < type->field_count(); ++i) {
    const pb::FieldDescriptor* field = type->field(i);
    if (field->message_type() != nullptr) describe(field->message_type(), seen, out);
    if (field->enum_type() != nullptr && seen.insert(std::string(field->enum_type()->full_name())).second) {
      pb::EnumDescriptorProto values;
      field->enum_type()->CopyTo(&values);
      out += values.SerializeAsString();
    }
  }
}

void load_types(FleetNodeFacts& facts) {
  const v1::DcclConfig& dccl = facts.node.config.dccl();
  dccl::Codec codec;
  dccl::install_plugin_codecs(codec.registry(), &dccl);
  std::vector<std::string> include_dirs(dccl.include_dirs().begin(), dccl.include_dirs().end());
  for (int k = 0; k < dccl.proto_files_size(); ++k) {
    const std::string path = "dccl.proto_files[" + std::to_string(k) + "]";
    std::vector<const dccl::TypeInfo*> types;
    try {
      types = codec.load(dccl.proto_files(k), include_dirs);
    } catch (const std::exception& e) {
      facts.loaded = false;
      facts.problem = "node " + facts.node.name + ": " + dccl.proto_files(k) + " does not load: " + e.what();
      facts.problem_where = origin_of(facts, path);
      return;
    }
    for (const dccl::TypeInfo* type : types) {
      FleetType known{type->name, type->omit_id ? -1 : type->id, "", origin_of(facts, path)};
      std::set<std::string> seen;
      describe(type->descriptor, seen, known.fingerprint);
      facts.types.push_back(std::move(known));
    }
  }
}

}  // namespace

core::Origin origin_of(const FleetNodeFacts& node, const std::string& path) {
  std::string at = path;
  while (!at.empty()) {
    auto it = node.node.config_where.find(at);
    if (it != node.node.config_where.end()) return it->second;
    size_t cut = at.find_last_of(".[");
    if (cut == std::string::npos) break;
    at.resize(cut);
  }
  return node.node.where;
}

FleetNodeFacts node_facts(const core::Fleet& fleet, const std::string& name) {
  FleetNodeFacts facts;
  try {
    facts.node = fleet.resolve(name);
  } catch (const core::ConfigError& e) {
    facts.problem = e.problem();
    facts.problem_where = core::Origin{e.file(), e.line()};
    return facts;
  }
  try {
    (void)core::node_config(fleet, name);  // as acommsd --fleet would load it
  } catch (const core::ConfigError& e) {
    facts.problem = "node " + name + ": " + e.problem();
    facts.problem_where = core::Origin{e.file(), e.line()};
    return facts;
  }
  facts.loaded = true;
  const v1::Config& config = facts.node.config;
  try {
    facts.id = core::node_id(config);
    facts.links = core::node_links(config);
  } catch (const std::exception& e) {
    facts.loaded = false;
    facts.problem = "node " + name + ": " + e.what();
    facts.problem_where = facts.node.where;
    return facts;
  }
  facts.id_where = facts.node.where;
  if (config.link_size() == 0) {
    facts.link_paths.push_back("");
    if (config.driver().modem_id() != 0) facts.id_where = origin_of(facts, "driver.modem_id");
  } else {
    for (int i = 0; i < config.link_size(); ++i) {
      const std::string path = "link[" + std::to_string(i) + "].";
      facts.link_paths.push_back(path);
      if (config.link(i).driver().modem_id() != 0 && facts.id_where.line == facts.node.where.line) {
        facts.id_where = origin_of(facts, path + "driver.modem_id");
      }
    }
  }
  load_types(facts);
  return facts;
}

std::pair<std::string, std::string> first_difference(const pb::Message& a, const std::string& a_prefix,
                                                     const pb::Message& b, const std::string& b_prefix) {
  core::RenderedText left = core::render_located(a, nullptr);
  core::RenderedText right = core::render_located(b, nullptr);
  auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    size_t start = 0;
    for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
      out.push_back(text.substr(start, end - start));
    }
    return out;
  };
  std::vector<std::string> l = lines(left.text), r = lines(right.text);
  for (size_t i = 0; i < std::max(l.size(), r.size()); ++i) {
    if (i < l.size() && i < r.size() && l[i] == r[i]) continue;
    // Past the end of one: point at the other's field, and the whole block in the shorter.
    std::string lp = i < l.size() ? left.line_paths[i] : "";
    std::string rp = i < r.size() ? right.line_paths[i] : "";
    return {a_prefix + lp, b_prefix + rp};
  }
  return {"", ""};
}

}  // namespace acomms::eval
