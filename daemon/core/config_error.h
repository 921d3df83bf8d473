#pragma once
// A configuration problem, located so that the person editing the file can go
// straight to it: "<file>:<line>:<column>: field '<path>': <what is wrong>".
//
// Thread-safe as any exception: set once when thrown, then only read.

#include <stdexcept>
#include <string>

namespace acomms::core {

class ConfigError : public std::runtime_error {
 public:
  // line and column are 1-based; 0 when the problem has no place in the file
  // (the file is missing, say).
  ConfigError(std::string file, int line, int column, std::string field, std::string problem);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  // Dotted path of the offending field ("grpc.tcp_listen"); empty if unknown.
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  int line_;
  int column_;
  std::string field_;
  std::string problem_;
};

}  // namespace acomms::core
