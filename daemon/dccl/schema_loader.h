// Schema loading: .proto files read at run time become the plans of DCCL
// types (type_plan.h), checked against DCCL's rules.
//
// Problem: a protobuf DescriptorPool keeps every file it has built and can
// never replace one. Loaded naively, a file that fails a DCCL rule would stay
// in the pool and come back unchanged when its corrected version is loaded,
// and a file edited after loading would silently keep its old meaning.
// Decision: every load parses and checks the file first in a throw-away
// trial pool; only a file that passes is built into this loader's pool.
// A file (or import) that differs from the version already built is refused
// by name, with the way out (another file name, or a restart).
//
// Invariants: loading is all or nothing; every problem found is reported,
// one per line ("file:line:col: text" for .proto syntax, "pkg.Msg.field:
// rule" for DCCL rules); plans and the indexes over them only grow.
//
// Thread safety: the find*() calls may run concurrently once loading is
// done; load() and add_include_dir() must not run concurrently with anything.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "dccl/registry.h"
#include "dccl/type_info.h"
#include "dccl/type_plan.h"

namespace google::protobuf {
class Descriptor;
}  // namespace google::protobuf

namespace acomms::dccl {

class SchemaLoader {
 public:
  // Include directories start with where dccl/option_extensions.proto lives
  // (see Codec()).
  SchemaLoader();
  ~SchemaLoader();
  SchemaLoader(const SchemaLoader&) = delete;
  SchemaLoader& operator=(const SchemaLoader&) = delete;

  CodecRegistry& registry();

  void add_include_dir(const std::string& dir);
  const std::vector<std::string>& include_dirs() const;

  // See Codec::load().
  std::vector<const TypeInfo*> load(const std::string& proto_file, const std::vector<std::string>& include_dirs);

  // Loaded plans; nullptr if none.
  const TypePlan* find(std::string_view full_name) const;
  const TypePlan* find(const google::protobuf::Descriptor* type) const;
  const TypePlan* find_id(int id) const;
  // See Codec::reserve_id().
  void reserve_id(int id, const std::string& owner);
  std::vector<const TypeInfo*> types() const;
  // See Codec::refused_types().
  const std::map<std::string, std::string>& refused_types() const;

 private:
  struct Pools;
  std::unique_ptr<Pools> pools_;
};

}  // namespace acomms::dccl
