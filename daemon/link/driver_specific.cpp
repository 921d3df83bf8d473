#include "link/driver_specific.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/unknown_field_set.h>

#include <vector>

namespace acomms::link {

std::string describe_driver_specific(const v1::ModemTransmission& request) {
  std::string names;
  auto add = [&names](const std::string& name) { names += (names.empty() ? "" : ", ") + name; };
  const google::protobuf::Reflection* reflection = request.GetReflection();
  std::vector<const google::protobuf::FieldDescriptor*> fields;
  reflection->ListFields(request, &fields);
  for (const auto* field : fields) {
    if (field->is_extension()) add(field->full_name());
  }
  // Extensions of a driver this binary does not link stay unknown fields.
  const google::protobuf::UnknownFieldSet& unknown = reflection->GetUnknownFields(request);
  for (int i = 0; i < unknown.field_count(); ++i) add("extension " + std::to_string(unknown.field(i).number()));
  return names.empty() ? "no extension" : names;
}

DriverSpecificResult driver_specific_error(DriverSpecificStatus status, std::string error,
                                           const v1::ModemTransmission& request) {
  return {status, std::move(error), request};
}

}  // namespace acomms::link
