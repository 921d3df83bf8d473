#include "dccl/registry.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <cctype>

#include "dccl/element_codec.h"

namespace acomms::dccl {
namespace gp = google::protobuf;

const gp::FieldDescriptor* FieldContext::extension_field(std::string_view full_name) const {
  if (pool == nullptr) return nullptr;
  const gp::FieldDescriptor* ext = pool->FindExtensionByName(std::string(full_name));
  if (ext == nullptr || raw_options == nullptr ||
      ext->containing_type() != raw_options->GetDescriptor()) {
    return nullptr;
  }
  return ext;
}

const gp::Message* FieldContext::extension_message(std::string_view full_name) const {
  const gp::FieldDescriptor* ext = extension_field(full_name);
  if (ext == nullptr || ext->cpp_type() != gp::FieldDescriptor::CPPTYPE_MESSAGE || ext->is_repeated()) {
    return nullptr;
  }
  return &raw_options->GetReflection()->GetMessage(*raw_options, ext);
}

void CodecRegistry::add(const std::string& name, FieldCodecFactory factory) {
  factories_[name] = std::move(factory);
}

const FieldCodecFactory* CodecRegistry::find(const std::string& name, int version,
                                             std::string* resolved) const {
  auto try_name = [&](const std::string& n) -> const FieldCodecFactory* {
    auto it = factories_.find(n);
    if (it == factories_.end()) return nullptr;
    if (resolved) *resolved = n;
    return &it->second;
  };
  bool ends_in_digit = !name.empty() && std::isdigit(static_cast<unsigned char>(name.back()));
  if (!ends_in_digit) {
    if (const FieldCodecFactory* f = try_name(name + std::to_string(version))) return f;
  }
  return try_name(name);
}

CodecRegistry CodecRegistry::with_builtins() {
  CodecRegistry r;
  for (int version : {2, 3, 4}) {
    auto factory = [version](const FieldContext& ctx) {
      FieldContext c = ctx;
      c.codec_version = version;
      return make_field(c, make_default_element, ctx.codec_version);
    };
    r.add("_default" + std::to_string(version), factory);
    r.add("dccl.default" + std::to_string(version), factory);
  }
  r.add("dccl.time", [](const FieldContext& ctx) { return make_field(ctx, make_time_element); });
  r.add("dccl.static", [](const FieldContext& ctx) { return make_field(ctx, make_static_element); });
  r.add("dccl.presence",
        [](const FieldContext& ctx) { return make_presence_field(ctx, make_default_element); });
  r.add("dccl.var_bytes", [](const FieldContext& ctx) { return make_field(ctx, make_var_bytes_element); });
  return r;
}

}  // namespace acomms::dccl
