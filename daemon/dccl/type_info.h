// What the codec knows about a loaded DCCL type: its id, sizes and the bit
// budget of every field (for `acommsctl dccl analyze` and for planning
// which messages fit in a modem frame).
//
// Thread-safe: plain values, filled once when a type loads and only read
// afterwards.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dccl/field_codec.h"

namespace google::protobuf {
class Descriptor;
class FieldDescriptor;
}  // namespace google::protobuf

namespace acomms::dccl {

struct FieldInfo {
  std::string path;   // "gv.Embed4.o.v"
  std::string codec;  // resolved codec name, e.g. "_default4"
  const google::protobuf::FieldDescriptor* field = nullptr;
  SizeBits bits;            // this field's share of the message (repeats included)
  bool in_head = false;
  int depth = 0;            // 0: field of the top-level message
  double resolution = 0;    // quantum of numeric values, 0 if not numeric
};

struct TypeInfo {
  std::string name;  // "gv.NavigationReport"
  const google::protobuf::Descriptor* descriptor = nullptr;
  int id = -1;  // -1 when omit_id
  bool omit_id = false;
  int codec_version = 4;
  uint32_t max_bytes = 0;  // the (dccl.msg) limit
  unsigned id_bits = 0;    // 0, 8 or 16
  SizeBits head;           // in_head fields (without the id)
  SizeBits body;
  std::vector<FieldInfo> fields;  // every field, embedded ones after their parent

  // Encoded size in bytes: head (id + in_head fields) padded to a byte, plus
  // body padded to a byte.
  uint64_t min_size_bytes() const { return (id_bits + head.min + 7) / 8 + (body.min + 7) / 8; }
  uint64_t max_size_bytes() const { return (id_bits + head.max + 7) / 8 + (body.max + 7) / 8; }
};

}  // namespace acomms::dccl
