// Typed access to a scalar field through protobuf reflection, singular or
// repeated, so element codecs can be templates over the C++ value type.
// Internal to the library.
#pragma once

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <cstdint>

namespace acomms::dccl {

template <typename T>
struct Access;

#define ACOMMS_DCCL_ACCESS(T, Name)                                                        \
  template <>                                                                              \
  struct Access<T> {                                                                       \
    static T get(const google::protobuf::Message& m, const google::protobuf::FieldDescriptor* f, \
                 int index) {                                                              \
      const google::protobuf::Reflection* r = m.GetReflection();                           \
      return index < 0 ? r->Get##Name(m, f) : r->GetRepeated##Name(m, f, index);           \
    }                                                                                      \
    static void put(google::protobuf::Message* m, const google::protobuf::FieldDescriptor* f, \
                    T v) {                                                                 \
      const google::protobuf::Reflection* r = m->GetReflection();                          \
      if (f->is_repeated()) {                                                              \
        r->Add##Name(m, f, v);                                                             \
      } else {                                                                             \
        r->Set##Name(m, f, v);                                                             \
      }                                                                                    \
    }                                                                                      \
  };

ACOMMS_DCCL_ACCESS(int32_t, Int32)
ACOMMS_DCCL_ACCESS(int64_t, Int64)
ACOMMS_DCCL_ACCESS(uint32_t, UInt32)
ACOMMS_DCCL_ACCESS(uint64_t, UInt64)
ACOMMS_DCCL_ACCESS(float, Float)
ACOMMS_DCCL_ACCESS(double, Double)
ACOMMS_DCCL_ACCESS(bool, Bool)

#undef ACOMMS_DCCL_ACCESS

}  // namespace acomms::dccl
