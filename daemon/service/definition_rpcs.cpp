// LoadDefinitions and ListTypes: which DCCL types the daemon knows.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>

#include <set>

#include "service/acomms_service.h"
#include "service/rpc_status.h"

namespace acomms::service {
namespace {

namespace pb = google::protobuf;

// The type's file and everything it imports, dependencies first (the order
// a DescriptorPool needs to build them).
void add_file(const pb::FileDescriptor* file, std::set<std::string>* seen, pb::FileDescriptorSet* set) {
  if (!seen->insert(file->name()).second) return;
  for (int i = 0; i < file->dependency_count(); ++i) add_file(file->dependency(i), seen, set);
  file->CopyTo(set->add_file());
}

void fill_type(const dccl::Codec& codec, const dccl::TypeInfo& info, bool fields, bool descriptors,
               v1::TypeInfo* out) {
  out->set_name(info.name);
  out->set_dccl_id(info.omit_id ? -1 : info.id);
  out->set_min_bytes(info.min_size_bytes());
  out->set_max_bytes(info.max_size_bytes());
  out->set_max_bytes_allowed(info.max_bytes);
  out->set_codec_version(info.codec_version);
  out->set_file(info.descriptor->file()->name());
  // The trailer's cost, so a budget shows what goes on the water.
  if (codec.authenticated(info.name)) out->set_auth_trailer_bits(codec.authenticator()->trailer_bytes() * 8);
  if (fields) {
    for (const dccl::FieldInfo& field : info.fields) {
      v1::FieldBudget* budget = out->add_fields();
      budget->set_path(field.path);
      budget->set_codec(field.codec);
      budget->set_min_bits(field.bits.min);
      budget->set_max_bits(field.bits.max);
      budget->set_in_head(field.in_head);
    }
  }
  if (descriptors) {
    pb::FileDescriptorSet set;
    std::set<std::string> seen;
    add_file(info.descriptor->file(), &seen, &set);
    out->set_descriptor_set(set.SerializeAsString());
  }
}

grpc::Status to_status(const DefinitionError& e) {
  switch (e.code) {
    case DefinitionError::Code::kNotFound: return {grpc::StatusCode::NOT_FOUND, e.what()};
    case DefinitionError::Code::kInvalid: return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
    case DefinitionError::Code::kStore: break;
  }
  return {grpc::StatusCode::UNAVAILABLE, e.what()};
}

}  // namespace

grpc::Status AcommsService::LoadDefinitions(grpc::ServerContext* context, const v1::LoadDefinitionsRequest* request,
                                            v1::LoadDefinitionsResponse* response) {
  if (grpc::Status denied = allowed(*context, "LoadDefinitions"); !denied.ok()) return denied;
  size_t text_bytes = 0;
  for (const auto& definition : request->inline_()) text_bytes += definition.text().size();
  if (text_bytes > 1024 * 1024) {
    return {grpc::StatusCode::INVALID_ARGUMENT, "inline definitions are larger than 1 MiB in all"};
  }
  // No Submit may look a type up while types are added, and the core
  // thread (which decodes received frames) runs the load itself.
  auto changing = node_.submitter.types_changing();
  try {
    std::vector<const dccl::TypeInfo*> types =
        node_.core.call([&] { return node_.definitions.load(*request); });
    for (const dccl::TypeInfo* info : types) fill_type(node_.codec, *info, true, false, response->add_types());
  } catch (const DefinitionError& e) {
    return to_status(e);
  }
  return grpc::Status::OK;
}

grpc::Status AcommsService::ListTypes(grpc::ServerContext* context, const v1::ListTypesRequest* request,
                                      v1::ListTypesResponse* response) {
  if (grpc::Status denied = allowed(*context, "ListTypes"); !denied.ok()) return denied;
  auto stable = node_.submitter.types_stable();
  if (request->types().empty()) {
    for (const dccl::TypeInfo* info : node_.codec.types()) {
      fill_type(node_.codec, *info, request->fields(), request->descriptors(), response->add_types());
    }
    return grpc::Status::OK;
  }
  for (const std::string& name : request->types()) {
    const dccl::TypeInfo* info = node_.codec.find_type(name);
    if (info == nullptr) return type_not_loaded(name);
    fill_type(node_.codec, *info, request->fields(), request->descriptors(), response->add_types());
  }
  return grpc::Status::OK;
}

}  // namespace acomms::service
