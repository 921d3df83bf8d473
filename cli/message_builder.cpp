#include "message_builder.h"

#include <google/protobuf/descriptor.pb.h>
#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>

#include <charconv>
#include <limits>
#include <stdexcept>
#include <vector>

#include "api_client.h"
#include "comma_list.h"
#include "dccl/hex.h"
#include "output.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace gp = google::protobuf;

namespace {

// Keeps the first problem: one is enough to say the daemon's set is bad.
class FirstError : public gp::DescriptorPool::ErrorCollector {
 public:
  void AddError(const std::string& filename, const std::string& element, const gp::Message*,
                ErrorLocation, const std::string& message) override {
    if (first.empty()) first = filename + ": " + element + ": " + message;
  }
  std::string first;
};

template <typename T>
T parse_integer(const std::string& text) {
  // Wide first, so that "300" for a uint8-like bound or "-1" for an
  // unsigned field gets a range message rather than "not a number".
  const char* end = text.data() + text.size();
  if constexpr (std::is_signed_v<T>) {
    int64_t value = 0;
    auto [ptr, error] = std::from_chars(text.data(), end, value);
    if (error != std::errc() || ptr != end) throw UsageError("\"" + text + "\" is not an integer");
    if (value < std::numeric_limits<T>::min() || value > std::numeric_limits<T>::max()) {
      throw UsageError(text + " does not fit the field's type");
    }
    return static_cast<T>(value);
  } else {
    if (!text.empty() && text[0] == '-') throw UsageError(text + " is negative; the field is unsigned");
    uint64_t value = 0;
    auto [ptr, error] = std::from_chars(text.data(), end, value);
    if (error != std::errc() || ptr != end) throw UsageError("\"" + text + "\" is not an integer");
    if (value > std::numeric_limits<T>::max()) throw UsageError(text + " does not fit the field's type");
    return static_cast<T>(value);
  }
}

double parse_real(const std::string& text) {
  double value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || ptr != end) throw UsageError("\"" + text + "\" is not a number");
  return value;
}

bool parse_bool(const std::string& text) {
  if (text == "true" || text == "1") return true;
  if (text == "false" || text == "0") return false;
  throw UsageError("\"" + text + "\" is not true or false");
}

std::string parse_hex(const std::string& text) {
  if (text.rfind("0x", 0) != 0 && text.rfind("0X", 0) != 0) {
    throw UsageError("bytes are written in hex with a 0x prefix, e.g. 0x0a1b");
  }
  try {
    return dccl::from_hex(std::string_view(text).substr(2));
  } catch (const std::invalid_argument& e) {
    throw UsageError("\"" + text + "\" is not hex: " + e.what());
  }
}

const gp::EnumValueDescriptor* parse_enum(const gp::EnumDescriptor* type, const std::string& text) {
  if (const auto* value = type->FindValueByName(text)) return value;
  throw UsageError("\"" + text + "\" is not one of " + enum_value_names(type));
}

// One scalar: the field's value when singular, one more element when repeated.
void put_scalar(gp::Message& message, const gp::FieldDescriptor* field, const std::string& text) {
  const gp::Reflection* r = message.GetReflection();
  const bool add = field->is_repeated();
  using F = gp::FieldDescriptor;
  switch (field->cpp_type()) {
    case F::CPPTYPE_INT32: {
      auto v = parse_integer<int32_t>(text);
      add ? r->AddInt32(&message, field, v) : r->SetInt32(&message, field, v);
      break;
    }
    case F::CPPTYPE_INT64: {
      auto v = parse_integer<int64_t>(text);
      add ? r->AddInt64(&message, field, v) : r->SetInt64(&message, field, v);
      break;
    }
    case F::CPPTYPE_UINT32: {
      auto v = parse_integer<uint32_t>(text);
      add ? r->AddUInt32(&message, field, v) : r->SetUInt32(&message, field, v);
      break;
    }
    case F::CPPTYPE_UINT64: {
      auto v = parse_integer<uint64_t>(text);
      add ? r->AddUInt64(&message, field, v) : r->SetUInt64(&message, field, v);
      break;
    }
    case F::CPPTYPE_DOUBLE: {
      double v = parse_real(text);
      add ? r->AddDouble(&message, field, v) : r->SetDouble(&message, field, v);
      break;
    }
    case F::CPPTYPE_FLOAT: {
      auto v = static_cast<float>(parse_real(text));
      add ? r->AddFloat(&message, field, v) : r->SetFloat(&message, field, v);
      break;
    }
    case F::CPPTYPE_BOOL: {
      bool v = parse_bool(text);
      add ? r->AddBool(&message, field, v) : r->SetBool(&message, field, v);
      break;
    }
    case F::CPPTYPE_ENUM: {
      const auto* v = parse_enum(field->enum_type(), text);
      add ? r->AddEnum(&message, field, v) : r->SetEnum(&message, field, v);
      break;
    }
    case F::CPPTYPE_STRING: {
      std::string v = field->type() == F::TYPE_BYTES ? parse_hex(text) : text;
      add ? r->AddString(&message, field, v) : r->SetString(&message, field, v);
      break;
    }
    case F::CPPTYPE_MESSAGE:
      throw std::logic_error("put_scalar on a message field");
  }
}

// Message fields take JSON. Each object is parsed into a message of the
// field's own type, so the parent's other required fields (not given yet)
// do not fail the parse; an array is split through google.protobuf.Value.
void parse_object(const std::string& json, gp::Message* into, const gp::FieldDescriptor* field) {
  auto status = gp::util::JsonStringToMessage(json, into);
  if (!status.ok()) {
    std::string why(status.message());
    if (why.rfind(": ", 0) == 0) why.erase(0, 2);
    throw UsageError("expected a JSON object of " + field->message_type()->full_name() + " (" + why + ")");
  }
}

void set_message_field(gp::Message& message, const gp::FieldDescriptor* field, const std::string& text) {
  const gp::Reflection* r = message.GetReflection();
  const gp::Message& prototype = *r->GetMessageFactory()->GetPrototype(field->message_type());
  if (!field->is_repeated()) {
    std::unique_ptr<gp::Message> value(prototype.New());
    parse_object(text, value.get(), field);
    r->MutableMessage(&message, field)->CopyFrom(*value);
    return;
  }
  gp::Value array;
  if (!gp::util::JsonStringToMessage(text, &array).ok() || array.kind_case() != gp::Value::kListValue) {
    throw UsageError("expected a JSON array of " + field->message_type()->full_name() + " objects, e.g. [{...}, {...}]");
  }
  std::vector<std::unique_ptr<gp::Message>> elements;
  for (const gp::Value& element : array.list_value().values()) {
    std::string json;
    (void)gp::util::MessageToJsonString(element, &json);
    elements.emplace_back(prototype.New());
    parse_object(json, elements.back().get(), field);
  }
  r->ClearField(&message, field);
  for (const auto& element : elements) r->AddMessage(&message, field)->CopyFrom(*element);
}

void collect_paths(const gp::Descriptor* type, const std::string& prefix, int depth, std::string* out) {
  for (int i = 0; i < type->field_count(); ++i) {
    const gp::FieldDescriptor* field = type->field(i);
    std::string path = prefix + field->name();
    // Singular messages are reached field by field; the depth limit stops
    // a recursive type from listing forever.
    if (field->message_type() != nullptr && !field->is_repeated() && depth < 6) {
      collect_paths(field->message_type(), path + ".", depth + 1, out);
    } else {
      *out += (out->empty() ? "" : ", ") + path;
    }
  }
}

}  // namespace

TypeSchema::TypeSchema(const std::string& descriptor_set, const std::string& type)
    : compiled_(*gp::DescriptorPool::generated_pool()), merged_(&sent_, &compiled_) {
  gp::FileDescriptorSet files;
  if (!files.ParseFromString(descriptor_set) || files.file_size() == 0) {
    throw std::runtime_error("the daemon sent no usable descriptors for " + type);
  }
  for (const auto& file : files.file()) sent_.Add(file);
  auto errors = std::make_unique<FirstError>();
  pool_ = std::make_unique<gp::DescriptorPool>(&merged_, errors.get());
  // Build every file now, while the error collector is alive, so a bad set
  // is reported here rather than as a missing field later.
  for (const auto& file : files.file()) {
    if (pool_->FindFileByName(file.name()) == nullptr) {
      throw std::runtime_error("the daemon's descriptors for " + type + " do not build: " + errors->first);
    }
  }
  type_ = pool_->FindMessageTypeByName(type);
  if (type_ == nullptr) throw std::runtime_error("the daemon's descriptors do not define " + type);
  options_ = std::make_unique<dccl::OptionReader>(pool_.get());
}

std::unique_ptr<gp::Message> TypeSchema::new_message() const {
  return std::unique_ptr<gp::Message>(factory_.GetPrototype(type_)->New());
}

dccl::FieldOptions TypeSchema::field_options(const gp::FieldDescriptor* field) {
  const gp::Message* raw = nullptr;
  return options_->field_options(field, &raw);
}

std::unique_ptr<TypeSchema> fetch_schema(ApiClient& client, const std::string& type) {
  v1::ListTypesRequest request;
  request.add_types(type);
  request.set_descriptors(true);
  v1::ListTypesResponse response = client.call(&v1::Acomms::Stub::ListTypes, request);
  for (const v1::TypeInfo& info : response.types()) {
    if (info.name() == type) return std::make_unique<TypeSchema>(info.descriptor_set(), type);
  }
  throw std::runtime_error("the daemon did not describe " + type);
}

std::pair<std::string, std::string> split_assignment(const std::string& argument) {
  size_t equals = argument.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw UsageError("\"" + argument + "\" is not field=value");
  }
  return {argument.substr(0, equals), argument.substr(equals + 1)};
}

void assign_path(gp::Message& message, const std::string& path, const std::string& text) {
  gp::Message* current = &message;
  size_t begin = 0;
  while (true) {
    size_t dot = path.find('.', begin);
    std::string name = path.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin);
    const gp::Descriptor* type = current->GetDescriptor();
    const gp::FieldDescriptor* field = type->FindFieldByName(name);
    if (field == nullptr) {
      throw UsageError("unknown field \"" + path.substr(0, dot) + "\" of " + message.GetDescriptor()->full_name() +
                       " (fields: " + assignable_paths(message.GetDescriptor()) + ")");
    }
    if (dot == std::string::npos) {
      try {
        set_field(*current, field, text);
      } catch (const UsageError& e) {
        throw UsageError(path + ": " + e.what());
      }
      return;
    }
    if (field->message_type() == nullptr) {
      throw UsageError(path.substr(0, dot) + " is a " + field_type_text(field) + ", not a message: \"" + path +
                       "\" names nothing");
    }
    if (field->is_repeated()) {
      throw UsageError(path.substr(0, dot) + " is repeated: give it whole as a JSON array, " +
                       path.substr(0, dot) + "='[{...}]'");
    }
    current = current->GetReflection()->MutableMessage(current, field);
    begin = dot + 1;
  }
}

void set_field(gp::Message& message, const gp::FieldDescriptor* field, const std::string& text) {
  if (field->message_type() != nullptr) {
    set_message_field(message, field, text);
    return;
  }
  if (!field->is_repeated()) {
    put_scalar(message, field, text);
    return;
  }
  // Parse everything before touching the field, so a bad element leaves
  // the previous value.
  std::unique_ptr<gp::Message> scratch(message.New());
  // "" is an empty list, not one empty item.
  if (!text.empty()) {
    for (const std::string& item : split_commas(text)) put_scalar(*scratch, field, item);
  }
  message.GetReflection()->ClearField(&message, field);
  message.GetReflection()->SwapFields(&message, scratch.get(), {field});
}

std::string assignable_paths(const gp::Descriptor* type) {
  std::string out;
  collect_paths(type, "", 0, &out);
  return out;
}

std::string field_type_text(const gp::FieldDescriptor* field) {
  std::string base;
  if (field->enum_type() != nullptr) {
    base = "enum " + field->enum_type()->name();
  } else if (field->message_type() != nullptr) {
    base = "message " + field->message_type()->name();
  } else {
    base = field->type_name();
  }
  return field->is_repeated() ? "repeated " + base : base;
}

std::string enum_value_names(const gp::EnumDescriptor* type) {
  std::string names;
  for (int i = 0; i < type->value_count(); ++i) names += (i ? ", " : "") + type->value(i)->name();
  return names;
}

}  // namespace acomms::cli
