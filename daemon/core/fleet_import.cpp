#include "core/fleet_import.h"

#include <stdexcept>

#include "core/fleet_merge.h"

namespace acomms::core {

namespace {

namespace pb = google::protobuf;

bool is_set(const pb::Message& message, const pb::FieldDescriptor* field) {
  return field->is_repeated() ? message.GetReflection()->FieldSize(message, field) > 0
                              : message.GetReflection()->HasField(message, field);
}

bool same_field(const pb::Message& a, const pb::Message& b, const pb::FieldDescriptor* field) {
  if (is_set(a, field) != is_set(b, field)) return false;
  if (!field->is_repeated()) return value_text(a, field, -1) == value_text(b, field, -1);
  const int n = a.GetReflection()->FieldSize(a, field);
  if (n != b.GetReflection()->FieldSize(b, field)) return false;
  for (int i = 0; i < n; ++i) {
    if (value_text(a, field, i) != value_text(b, field, i)) return false;
  }
  return true;
}

// Copies `field` whole from src to dst (dst's field cleared first).
void copy_field(const pb::Message& src, const pb::FieldDescriptor* field, pb::Message& dst) {
  dst.GetReflection()->ClearField(&dst, field);
  std::unique_ptr<pb::Message> only(src.New());
  only->CopyFrom(src);
  std::vector<const pb::FieldDescriptor*> fields;
  only->GetReflection()->ListFields(*only, &fields);
  for (const pb::FieldDescriptor* other : fields) {
    if (other != field) only->GetReflection()->ClearField(only.get(), other);
  }
  dst.MergeFrom(*only);
}

// What every message of `all` agrees on.
void common_part(const std::vector<const pb::Message*>& all, pb::Message& out) {
  const pb::Descriptor* type = out.GetDescriptor();
  for (int f = 0; f < type->field_count(); ++f) {
    const pb::FieldDescriptor* field = type->field(f);
    bool everywhere = true;
    for (const pb::Message* m : all) everywhere = everywhere && is_set(*m, field);
    if (!everywhere) continue;
    if (!field->is_repeated() && field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      std::vector<const pb::Message*> subs;
      for (const pb::Message* m : all) subs.push_back(&m->GetReflection()->GetMessage(*m, field));
      common_part(subs, *out.GetReflection()->MutableMessage(&out, field));
      continue;
    }
    bool equal = true;
    for (const pb::Message* m : all) equal = equal && same_field(*all.front(), *m, field);
    if (equal) copy_field(*all.front(), field, out);
  }
}

// What `node` has beyond `common`.
void own_part(const pb::Message& node, const pb::Message& common, pb::Message& out) {
  std::vector<const pb::FieldDescriptor*> fields;
  node.GetReflection()->ListFields(node, &fields);
  for (const pb::FieldDescriptor* field : fields) {
    if (!field->is_repeated() && field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      const pb::Message& sub = node.GetReflection()->GetMessage(node, field);
      const pb::Message& common_sub = common.GetReflection()->GetMessage(common, field);
      pb::Message* into = out.GetReflection()->MutableMessage(&out, field);
      own_part(sub, common_sub, *into);
      // Keep an empty message only where its presence is news.
      if (into->ByteSizeLong() == 0 && common.GetReflection()->HasField(common, field)) {
        out.GetReflection()->ClearField(&out, field);
      }
      continue;
    }
    if (!same_field(node, common, field)) copy_field(node, field, out);
  }
}

}  // namespace

v1::FleetFile import_fleet(const std::vector<std::pair<std::string, v1::Config>>& nodes) {
  if (nodes.empty()) throw std::invalid_argument("import needs at least one config");
  v1::FleetFile fleet;
  v1::FleetNode* common = fleet.add_node();
  common->set_name("common");
  common->set_abstract(true);
  std::vector<const pb::Message*> all;
  for (const auto& [name, config] : nodes) all.push_back(&config);
  common_part(all, *common->mutable_config());
  for (const auto& [name, config] : nodes) {
    for (int i = 1; i < fleet.node_size(); ++i) {
      if (fleet.node(i).name() == name) throw std::invalid_argument("two configs named \"" + name + "\"");
    }
    v1::FleetNode* node = fleet.add_node();
    node->set_name(name);
    node->add_parent("common");
    own_part(config, common->config(), *node->mutable_config());
  }
  return fleet;
}

}  // namespace acomms::core
