// Field-by-field merge (see environment_merge.h).
#include "gram/environment_merge.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/reflection.h>

#include <memory>
#include <stdexcept>

namespace acomms::gram {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;

// Replaces base's `field` with override's, as it is (zero, empty, or a
// whole sub-message): clear it, then merge a copy holding only that field.
// A zero proto3 scalar is not "set", so clearing is exactly taking it.
void copy_field(Message& base, const Message& override, const FieldDescriptor* field) {
  std::unique_ptr<Message> only(override.New());
  only->CopyFrom(override);
  std::vector<const FieldDescriptor*> all;
  only->GetReflection()->ListFields(*only, &all);
  for (const FieldDescriptor* other : all)
    if (other != field) only->GetReflection()->ClearField(only.get(), other);
  base.GetReflection()->ClearField(&base, field);
  base.MergeFrom(*only);
}

void merge_fields(Message& base, const Message& override) {
  const auto* reflection = override.GetReflection();
  std::vector<const FieldDescriptor*> fields;
  reflection->ListFields(override, &fields);  // the set (non-default) ones
  for (const FieldDescriptor* field : fields) {
    if (!field->is_repeated() && field->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE)
      merge_fields(*base.GetReflection()->MutableMessage(&base, field), reflection->GetMessage(override, field));
    else
      copy_field(base, override, field);
  }
}

// Takes the field at `path` (dotted) from override as it is.
void take_path(Message& base, const Message& override, const std::string& path, const std::string& full) {
  const auto dot = path.find('.');
  const std::string name = path.substr(0, dot);
  const FieldDescriptor* field = base.GetDescriptor()->FindFieldByName(name);
  if (field == nullptr)
    throw std::invalid_argument("override_mask: \"" + full + "\" names no field of acomms.gram.Environment (no \"" +
                                name + "\" in " + base.GetDescriptor()->full_name() + ")");
  if (dot == std::string::npos) {
    copy_field(base, override, field);
    return;
  }
  if (field->is_repeated() || field->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE)
    throw std::invalid_argument("override_mask: \"" + full + "\": " + name + " has no sub-fields");
  take_path(*base.GetReflection()->MutableMessage(&base, field), override.GetReflection()->GetMessage(override, field),
            path.substr(dot + 1), full);
}

}  // namespace

Environment merge_environment(const Environment& base, const Environment& override,
                              const std::vector<std::string>& mask) {
  Environment merged = base;
  merge_fields(merged, override);
  for (const std::string& path : mask) take_path(merged, override, path, path);
  return merged;
}

}  // namespace acomms::gram
