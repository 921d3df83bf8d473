// The compiled plan of one message type: its field codecs in declaration
// order plus its oneof selectors, built once at load time.
//
// MessageBody is used both for a top-level DCCL message (split into a head
// part holding the in_head fields and a body part) and for embedded
// messages. MessageCompiler builds them, resolving every field's codec
// through the registry and collecting every load-time error it finds rather
// than stopping at the first.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dccl/field_codec.h"
#include "dccl/options.h"
#include "dccl/type_info.h"

namespace google::protobuf {
class Descriptor;
class OneofDescriptor;
}  // namespace google::protobuf

namespace acomms::dccl {

class CodecRegistry;

class MessageBody {
 public:
  struct Slot {
    std::unique_ptr<FieldCodec> codec;
    const google::protobuf::FieldDescriptor* field = nullptr;
    int oneof = -1;  // index into oneofs_, -1 if not a oneof member
    std::string path;
  };
  struct Oneof {
    const google::protobuf::OneofDescriptor* oneof = nullptr;
    unsigned bits = 0;
    std::string path;
  };

  void add_slot(Slot slot) { slots_.push_back(std::move(slot)); }
  void add_oneof(Oneof oneof) { oneofs_.push_back(std::move(oneof)); }

  void encode(const google::protobuf::Message& msg, BitWriter& out, const EncodeContext& ctx) const;
  void decode(BitReader& in, google::protobuf::Message* msg, const DecodeContext& ctx) const;
  SizeBits size() const;
  bool empty() const { return slots_.empty() && oneofs_.empty(); }

 private:
  std::vector<Oneof> oneofs_;
  std::vector<Slot> slots_;
};

// Settings shared by every message compiled for one top-level type.
struct CompileSettings {
  int codec_version = 4;
  std::string codec_group;  // message-level default codec, "" for none
};

class MessageCompiler {
 public:
  MessageCompiler(const CodecRegistry* registry, OptionReader* options,
                  const google::protobuf::DescriptorPool* pool, CompileSettings settings);

  // Compiles the top-level type: in_head fields go to *head, the rest to *body.
  void compile_top(const google::protobuf::Descriptor* type, MessageBody* head, MessageBody* body);
  // Compiles an embedded message (every field in the body); `path` names
  // the field that holds it. Used by the built-in message codec.
  std::shared_ptr<MessageBody> compile_embedded(const google::protobuf::Descriptor* type,
                                                const std::string& path);

  // Errors found so far, one "path: rule" per entry.
  const std::vector<std::string>& errors() const { return errors_; }
  // Why the type is refused (TypeRefused from a field codec), one per field.
  const std::vector<std::string>& refusals() const { return refusals_; }
  std::vector<FieldInfo>& fields() { return fields_; }

 private:
  void compile_fields(const google::protobuf::Descriptor* type, const std::string& prefix,
                      MessageBody* head, MessageBody* body);
  std::unique_ptr<FieldCodec> compile_field(const google::protobuf::FieldDescriptor* field,
                                            const std::string& path, const FieldOptions& options,
                                            const google::protobuf::Message* raw,
                                            std::string* codec_name);

  const CodecRegistry* registry_;
  OptionReader* options_;
  const google::protobuf::DescriptorPool* pool_;
  CompileSettings settings_;
  std::vector<const google::protobuf::Descriptor*> stack_;  // to reject recursive types
  std::vector<std::string> errors_;
  std::vector<std::string> refusals_;
  std::vector<FieldInfo> fields_;
};

}  // namespace acomms::dccl
