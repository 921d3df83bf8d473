#pragma once
// The first error protobuf's text-format parser reports (later ones are
// usually consequences of it), for config files and fleet files alike:
// both turn it into a ConfigError naming the file, line and column.
//
// Thread-compatible: one per parse.

#include <optional>
#include <string>

#include <google/protobuf/io/tokenizer.h>

namespace acomms::core {

class FirstParseError : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, google::protobuf::io::ColumnNumber column, const std::string& message) override {
    if (!error_) error_ = Located{line, column, message};
  }
  struct Located {
    int line;  // 0-based, as the tokenizer counts
    int column;
    std::string message;
  };
  const std::optional<Located>& error() const { return error_; }

 private:
  std::optional<Located> error_;
};

}  // namespace acomms::core
