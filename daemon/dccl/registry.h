// Field codecs by name.
//
// A Codec owns one registry, filled with the built-in codecs
// (_default2/3/4, dccl.default2/3/4, dccl.time, dccl.static, dccl.presence,
// dccl.var_bytes); plugins add theirs before loading schemas that use them.
//
// Threads: filled (add) on one thread before schemas load; afterwards only
// read (find), so a Codec's concurrent encodes and decodes may share it.
#pragma once

#include <string>
#include <unordered_map>

#include "dccl/field_codec.h"

namespace acomms::dccl {

class CodecRegistry {
 public:
  // A registry holding only the built-in codecs.
  static CodecRegistry with_builtins();

  // Registers (or replaces) the codec called `name`.
  void add(const std::string& name, FieldCodecFactory factory);
  bool contains(const std::string& name) const { return factories_.count(name) != 0; }

  // DCCL's lookup: a name that does not end in a digit is tried as
  // name + version first ("dccl.time" -> "dccl.time4"), then as is.
  // Returns nullptr if neither exists; *resolved gets the name found.
  const FieldCodecFactory* find(const std::string& name, int version,
                                std::string* resolved = nullptr) const;

 private:
  std::unordered_map<std::string, FieldCodecFactory> factories_;
};

}  // namespace acomms::dccl
