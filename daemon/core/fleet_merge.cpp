#include "core/fleet_merge.h"

#include <algorithm>

namespace acomms::core {

namespace {

namespace pb = google::protobuf;
using Rule = RepeatedRule;

std::string element(const std::string& path, int index) { return path + "[" + std::to_string(index) + "]"; }

// Copies one scalar value of `field` from src (element src_index, -1:
// singular) into dst (appended when the field is repeated).
void copy_scalar(const pb::Message& src, const pb::FieldDescriptor* field, int src_index, pb::Message& dst) {
  const pb::Reflection* from = src.GetReflection();
  const pb::Reflection* to = dst.GetReflection();
  const bool repeated = field->is_repeated();
#define ACOMMS_COPY(CPP, Getter, Setter)                                                  \
  case pb::FieldDescriptor::CPPTYPE_##CPP:                                                \
    if (repeated) {                                                                       \
      to->Add##Setter(&dst, field, from->GetRepeated##Getter(src, field, src_index));     \
    } else {                                                                              \
      to->Set##Setter(&dst, field, from->Get##Getter(src, field));                        \
    }                                                                                     \
    return;
  switch (field->cpp_type()) {
    ACOMMS_COPY(INT32, Int32, Int32)
    ACOMMS_COPY(INT64, Int64, Int64)
    ACOMMS_COPY(UINT32, UInt32, UInt32)
    ACOMMS_COPY(UINT64, UInt64, UInt64)
    ACOMMS_COPY(DOUBLE, Double, Double)
    ACOMMS_COPY(FLOAT, Float, Float)
    ACOMMS_COPY(BOOL, Bool, Bool)
    ACOMMS_COPY(ENUM, EnumValue, EnumValue)
    ACOMMS_COPY(STRING, String, String)
    case pb::FieldDescriptor::CPPTYPE_MESSAGE:
      break;
  }
#undef ACOMMS_COPY
}

const RepeatedFieldRule& rule_of(const pb::FieldDescriptor* field) {
  static const RepeatedFieldRule kFallback{Rule::kReplace, {}};
  auto it = repeated_rules().find(std::string(field->full_name()));
  return it == repeated_rules().end() ? kFallback : it->second;
}

std::string key_of(const pb::Message& entry, const std::vector<std::string>& key_fields) {
  std::string key;
  for (const std::string& name : key_fields) {
    const pb::FieldDescriptor* field = entry.GetDescriptor()->FindFieldByName(name);
    const bool set = field != nullptr && entry.GetReflection()->HasField(entry, field);
    key += name + "=" + (set ? value_text(entry, field, -1) : "-") + ";";
  }
  return key;
}

void merge_message(const pb::Message& src, const Provenance& src_where, const std::string& src_path,
                   pb::Message& dst, Provenance& dst_where, const std::string& dst_path);

void take_origin(const Provenance& src_where, const std::string& src_path, Provenance& dst_where,
                 const std::string& dst_path) {
  auto it = src_where.find(src_path);
  if (it != src_where.end()) dst_where[dst_path] = it->second;
}

// Appends element `index` of src's repeated `field` to dst's.
void append_element(const pb::Message& src, const pb::FieldDescriptor* field, int index, const Provenance& src_where,
                    const std::string& src_field_path, pb::Message& dst, Provenance& dst_where,
                    const std::string& dst_field_path) {
  const int at = dst.GetReflection()->FieldSize(dst, field);
  const std::string from = element(src_field_path, index);
  const std::string to = element(dst_field_path, at);
  take_origin(src_where, from, dst_where, to);
  if (field->cpp_type() != pb::FieldDescriptor::CPPTYPE_MESSAGE) {
    copy_scalar(src, field, index, dst);
    return;
  }
  pb::Message* added = dst.GetReflection()->AddMessage(&dst, field);
  merge_message(src.GetReflection()->GetRepeatedMessage(src, field, index), src_where, from + ".", *added, dst_where,
                to + ".");
}

void erase_under(Provenance& where, const std::string& prefix) {
  for (auto it = where.lower_bound(prefix); it != where.end() && it->first.compare(0, prefix.size(), prefix) == 0;) {
    it = where.erase(it);
  }
}

void merge_repeated(const pb::Message& src, const pb::FieldDescriptor* field, const Provenance& src_where,
                    const std::string& src_path, pb::Message& dst, Provenance& dst_where, const std::string& dst_path) {
  const pb::Reflection* from = src.GetReflection();
  const pb::Reflection* to = dst.GetReflection();
  const std::string src_field = src_path + field->name();
  const std::string dst_field = dst_path + field->name();
  const RepeatedFieldRule& rule = rule_of(field);
  const int count = from->FieldSize(src, field);
  if (rule.rule == Rule::kReplace) {
    to->ClearField(&dst, field);
    erase_under(dst_where, dst_field + "[");
  }
  std::map<std::string, int> seen;  // kKeyed: key -> how many src entries had it so far
  for (int i = 0; i < count; ++i) {
    if (rule.rule == Rule::kAppendUnique) {
      const std::string value = value_text(src, field, i);
      bool present = false;
      for (int j = 0; j < to->FieldSize(dst, field) && !present; ++j) present = value_text(dst, field, j) == value;
      if (present) continue;
    }
    if (rule.rule == Rule::kKeyed && field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      const pb::Message& entry = from->GetRepeatedMessage(src, field, i);
      const std::string key = key_of(entry, rule.key_fields);
      int occurrence = seen[key]++;
      int match = -1;
      for (int j = 0; j < to->FieldSize(dst, field); ++j) {
        if (key_of(to->GetRepeatedMessage(dst, field, j), rule.key_fields) == key && occurrence-- == 0) {
          match = j;
          break;
        }
      }
      if (match >= 0) {
        take_origin(src_where, element(src_field, i), dst_where, element(dst_field, match));
        merge_message(entry, src_where, element(src_field, i) + ".", *to->MutableRepeatedMessage(&dst, field, match),
                      dst_where, element(dst_field, match) + ".");
        continue;
      }
    }
    append_element(src, field, i, src_where, src_field, dst, dst_where, dst_field);
  }
}

void merge_message(const pb::Message& src, const Provenance& src_where, const std::string& src_path,
                   pb::Message& dst, Provenance& dst_where, const std::string& dst_path) {
  std::vector<const pb::FieldDescriptor*> fields;
  src.GetReflection()->ListFields(src, &fields);
  for (const pb::FieldDescriptor* field : fields) {
    if (field->is_repeated()) {
      merge_repeated(src, field, src_where, src_path, dst, dst_where, dst_path);
      continue;
    }
    take_origin(src_where, src_path + field->name(), dst_where, dst_path + field->name());
    if (field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      merge_message(src.GetReflection()->GetMessage(src, field), src_where, src_path + field->name() + ".",
                    *dst.GetReflection()->MutableMessage(&dst, field), dst_where, dst_path + field->name() + ".");
    } else {
      copy_scalar(src, field, -1, dst);
    }
  }
}

}  // namespace

std::string value_text(const pb::Message& message, const pb::FieldDescriptor* field, int index) {
  std::string text;
  pb::TextFormat::Printer printer;
  printer.SetSingleLineMode(true);
  printer.PrintFieldValueToString(message, field, index, &text);
  return text;
}

std::string to_string(const Origin& origin) { return origin.file + ":" + std::to_string(origin.line); }

const std::map<std::string, RepeatedFieldRule>& repeated_rules() {
  // One line per repeated field reachable from acomms.v1.Config (and
  // FleetKeys); the comment of each field in its .proto says the same.
  static const std::map<std::string, RepeatedFieldRule> rules = {
      // The cycle: the n-th slot of a src merges into the n-th inherited one.
      {"acomms.v1.MacConfig.slot", {Rule::kKeyed, {"src"}}},
      {"acomms.v1.DcclConfig.proto_files", {Rule::kAppendUnique, {}}},
      {"acomms.v1.DcclConfig.include_dirs", {Rule::kAppendUnique, {}}},
      {"acomms.v1.DcclConfig.crypto_exempt_ids", {Rule::kAppendUnique, {}}},
      {"acomms.v1.DcclConfig.arithmetic_models", {Rule::kKeyed, {"name"}}},
      // Routes are tried in order: a list is one decision, replaced whole.
      {"acomms.v1.QueueTypeConfig.route", {Rule::kReplace, {}}},
      {"acomms.v1.QueueConfig.type", {Rule::kKeyed, {"type"}}},
      {"acomms.v1.QueueConfig.route", {Rule::kReplace, {}}},
      {"acomms.v1.TelemetryConfig.receiver", {Rule::kReplace, {}}},
      {"acomms.v1.TelemetryConfig.region_min_m", {Rule::kReplace, {}}},
      {"acomms.v1.TelemetryConfig.region_max_m", {Rule::kReplace, {}}},
      {"acomms.v1.AuthConfig.type", {Rule::kKeyed, {"type"}}},
      {"acomms.v1.AuthConfig.client", {Rule::kKeyed, {"common_name"}}},
      {"acomms.v1.Config.link", {Rule::kKeyed, {"name"}}},
      {"acomms.v1.LinkRoute.link", {Rule::kReplace, {}}},
      {"acomms.v1.RoutingConfig.route", {Rule::kKeyed, {"dest", "dest_min", "dest_max"}}},
      // The fleet's digests are one list, set where the fleet agrees on it.
      {"acomms.v1.ConsistencyConfig.expected_digest", {Rule::kReplace, {}}},
      {"acomms.drivers.IridiumShoreDriverConfig.modems", {Rule::kKeyed, {"imei"}}},
      // NVRAM lines: later ones win in the modem, so a class adds to the cruise's.
      {"acomms.drivers.MicroModemDriverConfig.cfg", {Rule::kAppend, {}}},
      {"acomms.drivers.MicroModemDriverConfig.mm1_modems", {Rule::kReplace, {}}},
      // A moored modem's position: a level may move one or add another.
      {"acomms.drivers.MicroModemPrediction.fixed", {Rule::kKeyed, {"modem"}}},
      // Each node's neighbours differ: the node's own list is the list.
      {"acomms.drivers.SimDriverConfig.peers", {Rule::kReplace, {}}},
      {"acomms.drivers.UdpDriverConfig.peers", {Rule::kReplace, {}}},
      {"acomms.drivers.SimPhysicsConfig.reception", {Rule::kKeyed, {"rate"}}},
      {"acomms.codecs.v1.ArithmeticModel.frequency", {Rule::kReplace, {}}},
      {"acomms.codecs.v1.ArithmeticModel.value_bound", {Rule::kReplace, {}}},
      // A profile or a bottom is one measurement, never a sum of two.
      {"acomms.gram.Environment.sound_speed", {Rule::kReplace, {}}},
      {"acomms.gram.Environment.bathymetry", {Rule::kReplace, {}}},
      {"acomms.gram.Environment.receiver_depth_m", {Rule::kReplace, {}}},
      {"acomms.gram.Environment.receiver_range_m", {Rule::kReplace, {}}},
      {"acomms.v1.FleetKeys.key_id", {Rule::kReplace, {}}},
  };
  return rules;
}

void record_provenance(const pb::Message& message, const pb::TextFormat::ParseInfoTree& tree, const std::string& file,
                       Provenance& into, const std::string& prefix) {
  std::vector<const pb::FieldDescriptor*> fields;
  message.GetReflection()->ListFields(message, &fields);
  for (const pb::FieldDescriptor* field : fields) {
    const std::string path = prefix + field->name();
    const bool is_message = field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE;
    const int count = field->is_repeated() ? message.GetReflection()->FieldSize(message, field) : 1;
    for (int i = 0; i < count; ++i) {
      const int index = field->is_repeated() ? i : -1;
      const std::string here = field->is_repeated() ? element(path, i) : path;
      pb::TextFormat::ParseLocation location = tree.GetLocation(field, index);
      if (location.line >= 0) into[here] = Origin{file, location.line + 1};
      if (!is_message) continue;
      const pb::TextFormat::ParseInfoTree* nested = tree.GetTreeForNested(field, index);
      const pb::Message& sub = field->is_repeated() ? message.GetReflection()->GetRepeatedMessage(message, field, i)
                                                    : message.GetReflection()->GetMessage(message, field);
      if (nested != nullptr) record_provenance(sub, *nested, file, into, here + ".");
    }
  }
}

void merge_located(const pb::Message& src, const Provenance& src_where, pb::Message& dst, Provenance& dst_where) {
  merge_message(src, src_where, "", dst, dst_where, "");
}

}  // namespace acomms::core
