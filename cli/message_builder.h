#pragma once
// Building a DCCL message on the client without its .proto: the daemon
// hands out each type's descriptors (ListTypes descriptors=true), from which
// a DynamicMessage is made and filled from "field=value" text.

#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor_database.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/message.h>

#include <memory>
#include <string>
#include <utility>

#include "dccl/options.h"

namespace acomms::cli {

class ApiClient;

// One DCCL type, described by the daemon: its descriptors, and the
// (dccl.field) options (bounds) of its fields.
class TypeSchema {
 public:
  // `descriptor_set`: a serialized FileDescriptorSet holding `type`.
  // Throws std::runtime_error if it does not build or lacks the type.
  TypeSchema(const std::string& descriptor_set, const std::string& type);
  TypeSchema(const TypeSchema&) = delete;
  TypeSchema& operator=(const TypeSchema&) = delete;

  const google::protobuf::Descriptor* type() const { return type_; }
  std::unique_ptr<google::protobuf::Message> new_message() const;
  // The field's (dccl.field) options, defaults when it has none.
  dccl::FieldOptions field_options(const google::protobuf::FieldDescriptor* field);

 private:
  google::protobuf::SimpleDescriptorDatabase sent_;
  // descriptor.proto, when the set leaves it out: it is compiled in.
  google::protobuf::DescriptorPoolDatabase compiled_;
  google::protobuf::MergedDescriptorDatabase merged_;
  std::unique_ptr<google::protobuf::DescriptorPool> pool_;
  mutable google::protobuf::DynamicMessageFactory factory_;  // caches prototypes
  std::unique_ptr<dccl::OptionReader> options_;
  const google::protobuf::Descriptor* type_ = nullptr;
};

// Asks the daemon for `type`'s descriptors. RpcError NOT_FOUND when the
// type is not loaded.
std::unique_ptr<TypeSchema> fetch_schema(ApiClient& client, const std::string& type);

// "header.time=12.5" -> {"header.time", "12.5"}. UsageError without '='.
std::pair<std::string, std::string> split_assignment(const std::string& argument);

// Sets the field at dotted `path` of `message` from text (see set_field).
// UsageError names the path and, for an unknown field, the valid ones.
void assign_path(google::protobuf::Message& message, const std::string& path, const std::string& text);

// Sets one field from text, the way a person types it:
//   numbers   12, -3, 0.25          bool   true / false
//   enums     the value's name      bytes  hex, 0x0a1b
//   strings   as given              repeated  comma-separated, "" for none
//   messages  a JSON object (repeated: a JSON array of them)
// Throws UsageError("<what it accepts>") without the field's name.
void set_field(google::protobuf::Message& message, const google::protobuf::FieldDescriptor* field,
               const std::string& text);

// Every path assign_path accepts for `type`, comma-separated.
std::string assignable_paths(const google::protobuf::Descriptor* type);

// "int32", "double", "enum Mode", "message Header", "repeated uint32".
std::string field_type_text(const google::protobuf::FieldDescriptor* field);

// "IDLE, SURVEY, RETURN".
std::string enum_value_names(const google::protobuf::EnumDescriptor* type);

}  // namespace acomms::cli
