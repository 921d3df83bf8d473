#include "daemon_config.h"

#include <fstream>
#include <stdexcept>

namespace acomms::testing {

std::string DaemonConfig::text() const {
  std::string out = "data_dir: \"" + data_dir.string() + "\"\n";
  out += "grpc { unix_socket: \"" + unix_socket + "\"";
  if (!grpc_extra.empty()) out += " " + grpc_extra;
  out += " }\n";
  if (!proto_file.empty()) out += "dccl { proto_files: \"" + proto_file + "\" }\n";
  return out + rest;
}

void DaemonConfig::write(const std::filesystem::path& file) const {
  std::ofstream out(file, std::ios::trunc);
  out << text();
  if (!out.flush()) throw std::runtime_error("cannot write the daemon config " + file.string());
}

}  // namespace acomms::testing
