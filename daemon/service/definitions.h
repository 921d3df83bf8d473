#pragma once
// What LoadDefinitions calls: the node's DCCL definitions as the API adds
// to them.
//
// The problem: a load writes files, makes queues and records the files in
// the store, none of which is the service's business (it parses, makes one
// call and answers). The decision: the service sees only this face; the
// node implements it (node/definition_loader.h) and hands it over.
//
// Not thread-safe: load() runs on the core thread, with no Submit looking
// a type up meanwhile (queue::Submitter::types_changing()).

#include <stdexcept>
#include <string>
#include <vector>

#include "acomms/v1/acomms.pb.h"
#include "dccl/type_info.h"

namespace acomms::service {

// A refused load: `code` is the gRPC status it maps to.
struct DefinitionError : std::runtime_error {
  enum class Code { kNotFound, kInvalid, kStore };
  DefinitionError(Code code, const std::string& what) : std::runtime_error(what), code(code) {}
  Code code;
};

class Definitions {
 public:
  virtual ~Definitions() = default;

  // Loads the request's files in order, makes queues for new types and
  // keeps the files for the next start. Returns the types loaded. Throws
  // DefinitionError.
  virtual std::vector<const dccl::TypeInfo*> load(const v1::LoadDefinitionsRequest& request) = 0;
};

}  // namespace acomms::service
