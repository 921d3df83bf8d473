#pragma once
// Field roles: which fields of a DCCL message say who sent it, who it is
// for and when it was made. DCCL messages have no fixed header, so each
// type names its own (config: QueueRoles); the queue needs the destination
// to build frames and to filter what it receives.

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"

namespace acomms::queue {

inline constexpr int32_t kBroadcast = 0;

class MessageRoles {
 public:
  MessageRoles() = default;
  // Resolves the configured field paths in `type`. Throws
  // std::invalid_argument naming the type, the path and what is wrong.
  MessageRoles(const google::protobuf::Descriptor* type, const v1::QueueRoles& config);

  // The source modem id, or -1 when the type has no source role or the
  // field is unset.
  int32_t source(const google::protobuf::Message& message) const;
  // The destination modem id: the field, else the static destination, else
  // broadcast.
  int32_t destination(const google::protobuf::Message& message) const;
  // Seconds since the Unix epoch, when the type has a set timestamp field.
  std::optional<double> timestamp(const google::protobuf::Message& message) const;
  // Whether the type names a timestamp field at all.
  bool has_timestamp() const { return !timestamp_.empty(); }

  // What a sender fills in before encoding: its own id as source and the
  // current time as timestamp, for role fields the client left unset.
  void fill_unset(google::protobuf::Message* message, int32_t own_id, double now) const;

 private:
  using Path = std::vector<const google::protobuf::FieldDescriptor*>;
  static Path resolve(const google::protobuf::Descriptor* type, const std::string& path,
                      const char* role, bool numeric_time);
  // The message holding the last field of `path`, or nullptr if a parent is unset.
  static const google::protobuf::Message* holder(const google::protobuf::Message& message,
                                                 const Path& path);

  Path source_, destination_, timestamp_;
  int32_t static_destination_ = kBroadcast;
};

}  // namespace acomms::queue
