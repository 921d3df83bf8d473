#include "queue/roles.h"

#include <sstream>
#include <stdexcept>

namespace acomms::queue {
namespace {

namespace pb = google::protobuf;

bool is_integer(const pb::FieldDescriptor* field) {
  switch (field->cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_INT32:
    case pb::FieldDescriptor::CPPTYPE_INT64:
    case pb::FieldDescriptor::CPPTYPE_UINT32:
    case pb::FieldDescriptor::CPPTYPE_UINT64:
      return true;
    default:
      return false;
  }
}

int64_t get_integer(const pb::Message& m, const pb::FieldDescriptor* f) {
  const pb::Reflection* r = m.GetReflection();
  switch (f->cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_INT32: return r->GetInt32(m, f);
    case pb::FieldDescriptor::CPPTYPE_INT64: return r->GetInt64(m, f);
    case pb::FieldDescriptor::CPPTYPE_UINT32: return r->GetUInt32(m, f);
    case pb::FieldDescriptor::CPPTYPE_UINT64: return static_cast<int64_t>(r->GetUInt64(m, f));
    default: return 0;
  }
}

void set_integer(pb::Message* m, const pb::FieldDescriptor* f, int64_t v) {
  const pb::Reflection* r = m->GetReflection();
  switch (f->cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_INT32: r->SetInt32(m, f, static_cast<int32_t>(v)); break;
    case pb::FieldDescriptor::CPPTYPE_INT64: r->SetInt64(m, f, v); break;
    case pb::FieldDescriptor::CPPTYPE_UINT32: r->SetUInt32(m, f, static_cast<uint32_t>(v)); break;
    case pb::FieldDescriptor::CPPTYPE_UINT64: r->SetUInt64(m, f, static_cast<uint64_t>(v)); break;
    default: break;
  }
}

bool has(const pb::Message& m, const pb::FieldDescriptor* f) {
  return m.GetReflection()->HasField(m, f);
}

}  // namespace

MessageRoles::Path MessageRoles::resolve(const pb::Descriptor* type, const std::string& path,
                                         const char* role, bool numeric_time) {
  Path fields;
  if (path.empty()) return fields;
  auto fail = [&](const std::string& problem) {
    throw std::invalid_argument("queue " + type->full_name() + ": " + role + " field \"" + path +
                                "\" " + problem);
  };
  std::istringstream parts(path);
  const pb::Descriptor* current = type;
  for (std::string name; std::getline(parts, name, '.');) {
    if (current == nullptr) fail("goes through a field that is not a message");
    const pb::FieldDescriptor* field = current->FindFieldByName(name);
    if (field == nullptr) fail("does not exist (no field \"" + name + "\" in " + current->full_name() + ")");
    if (field->is_repeated()) fail("is repeated; a role needs a single value");
    fields.push_back(field);
    current = field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE ? field->message_type() : nullptr;
  }
  const pb::FieldDescriptor* last = fields.back();
  bool ok = is_integer(last) || (numeric_time && (last->cpp_type() == pb::FieldDescriptor::CPPTYPE_DOUBLE ||
                                                  last->cpp_type() == pb::FieldDescriptor::CPPTYPE_FLOAT));
  if (!ok) fail(numeric_time ? "must be a number (seconds, or integer microseconds)" : "must be an integer");
  return fields;
}

MessageRoles::MessageRoles(const pb::Descriptor* type, const v1::QueueRoles& config)
    : source_(resolve(type, config.source_field(), "source", false)),
      destination_(resolve(type, config.destination_field(), "destination", false)),
      timestamp_(resolve(type, config.timestamp_field(), "timestamp", true)),
      static_destination_(config.has_static_destination() ? config.static_destination() : kBroadcast) {
  if (!destination_.empty() && config.has_static_destination()) {
    throw std::invalid_argument("queue " + type->full_name() +
                                ": set destination_field or static_destination, not both");
  }
}

const pb::Message* MessageRoles::holder(const pb::Message& message, const Path& path) {
  const pb::Message* current = &message;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    if (!has(*current, path[i])) return nullptr;
    current = &current->GetReflection()->GetMessage(*current, path[i]);
  }
  return current;
}

int32_t MessageRoles::source(const pb::Message& message) const {
  if (source_.empty()) return -1;
  const pb::Message* m = holder(message, source_);
  if (m == nullptr || !has(*m, source_.back())) return -1;
  return static_cast<int32_t>(get_integer(*m, source_.back()));
}

int32_t MessageRoles::destination(const pb::Message& message) const {
  if (destination_.empty()) return static_destination_;
  const pb::Message* m = holder(message, destination_);
  // An unset destination field means what its default says (usually 0: broadcast).
  if (m == nullptr) return kBroadcast;
  return static_cast<int32_t>(get_integer(*m, destination_.back()));
}

std::optional<double> MessageRoles::timestamp(const pb::Message& message) const {
  if (timestamp_.empty()) return std::nullopt;
  const pb::Message* m = holder(message, timestamp_);
  const pb::FieldDescriptor* f = timestamp_.back();
  if (m == nullptr || !has(*m, f)) return std::nullopt;
  switch (f->cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_DOUBLE: return m->GetReflection()->GetDouble(*m, f);
    case pb::FieldDescriptor::CPPTYPE_FLOAT: return m->GetReflection()->GetFloat(*m, f);
    default: return static_cast<double>(get_integer(*m, f)) / 1e6;  // DCCL's integer time: microseconds
  }
}

void MessageRoles::fill_unset(pb::Message* message, int32_t own_id, double now) const {
  auto mutable_holder = [&](const Path& path) {
    pb::Message* current = message;
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      current = current->GetReflection()->MutableMessage(current, path[i]);
    }
    return current;
  };
  if (!source_.empty() && source(*message) < 0) {
    set_integer(mutable_holder(source_), source_.back(), own_id);
  }
  if (!timestamp_.empty() && !timestamp(*message)) {
    pb::Message* m = mutable_holder(timestamp_);
    const pb::FieldDescriptor* f = timestamp_.back();
    switch (f->cpp_type()) {
      case pb::FieldDescriptor::CPPTYPE_DOUBLE: m->GetReflection()->SetDouble(m, f, now); break;
      case pb::FieldDescriptor::CPPTYPE_FLOAT: m->GetReflection()->SetFloat(m, f, static_cast<float>(now)); break;
      default: set_integer(m, f, static_cast<int64_t>(now * 1e6)); break;
    }
  }
}

}  // namespace acomms::queue
