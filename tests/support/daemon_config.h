#pragma once
// The config file of an acommsd started by an integration test.
//
// Every integration test wrote the same head by hand (where the daemon
// keeps its store, the unix socket it answers on, often the .proto files
// it loads) before the part the test is about (driver, MAC, queues, GRAM).
// The head is written here, quoted once; the test passes the rest as text.
// Fields of a protobuf text file may come in any order, so `rest` may also
// hold top-level fields such as log_level.
//
// Thread-compatible: a value type.

#include <filesystem>
#include <string>

namespace acomms::testing {

struct DaemonConfig {
  std::filesystem::path data_dir;  // data_dir
  std::string unix_socket;         // grpc.unix_socket
  std::string proto_file;          // dccl.proto_files, if not empty
  std::string grpc_extra;          // more of grpc { }, e.g. tcp_listen
  std::string rest;                // the rest of the file, as text

  std::string text() const;
  // Writes text() to `file` (replacing it); throws std::runtime_error if it
  // cannot be written.
  void write(const std::filesystem::path& file) const;
};

}  // namespace acomms::testing
