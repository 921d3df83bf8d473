// The standard (dccl.msg) and (dccl.field) options, read once at load time.
//
// Options live in dccl/option_extensions.proto, which is loaded at run time,
// so there is no generated C++ class for them. These structs hold the values
// the built-in codecs need; the raw option message (with any codec-specific
// extensions) stays available to plugin codecs through FieldContext.
//
// Thread-safe: plain values, filled once while a schema loads and only read
// afterwards.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace google::protobuf {
class Descriptor;
class DescriptorPool;
class DynamicMessageFactory;
class FieldDescriptor;
class Message;
}  // namespace google::protobuf

namespace acomms::dccl {

struct MessageOptions {
  bool present = false;  // the message has a (dccl.msg) option at all
  bool has_id = false;
  int32_t id = 0;
  bool has_max_bytes = false;
  uint32_t max_bytes = 0;
  std::string codec;
  std::string codec_group;
  bool has_codec_version = false;
  int32_t codec_version = 0;
  bool omit_id = false;
};

struct FieldOptions {
  bool has_codec = false;
  std::string codec = "_default";
  bool omit = false;
  bool in_head = false;
  bool has_precision = false;
  int32_t precision = 0;
  bool has_min = false;
  double min = 0;
  bool has_max = false;
  double max = 0;
  uint32_t num_days = 1;
  std::string static_value;
  bool has_max_length = false;
  uint32_t max_length = 0;
  bool has_max_repeat = false;
  uint32_t max_repeat = 0;
  bool packed_enum = true;
  bool has_resolution = false;
  double resolution = 1;
  uint32_t min_repeat = 0;
  bool has_dynamic_conditions = false;  // (dccl.field).dynamic_conditions given
};

// Reads options of descriptors that belong to `pool`, which must contain
// dccl/option_extensions.proto. The option messages are parsed into dynamic
// messages owned by this object, so references stay valid while it lives.
class OptionReader {
 public:
  explicit OptionReader(const google::protobuf::DescriptorPool* pool);
  ~OptionReader();

  // False if dccl/option_extensions.proto is not in the pool.
  bool available() const { return field_ext_ != nullptr && msg_ext_ != nullptr; }

  MessageOptions message_options(const google::protobuf::Descriptor* type);
  // `raw` receives the dccl.DCCLFieldOptions message (default instance when
  // the field has no (dccl.field) option).
  FieldOptions field_options(const google::protobuf::FieldDescriptor* field,
                             const google::protobuf::Message** raw);

 private:
  const google::protobuf::Message& extension_of(const google::protobuf::Message& options,
                                                const char* options_type,
                                                const google::protobuf::FieldDescriptor* ext);

  const google::protobuf::DescriptorPool* pool_;
  std::unique_ptr<google::protobuf::DynamicMessageFactory> factory_;
  const google::protobuf::FieldDescriptor* field_ext_ = nullptr;
  const google::protobuf::FieldDescriptor* msg_ext_ = nullptr;
  std::vector<std::unique_ptr<google::protobuf::Message>> owned_;
};

}  // namespace acomms::dccl
