// Fortran list-directed input, as BELLHOP's .env and side files are written.
//
// Problem: these files are read record by record with READ(*,*): values
// separated by blanks or commas, strings in quotes, '/' ends a record early
// (the values not yet read keep their defaults), '!' starts a comment, and a
// record continues on the following lines until its values are read. Each
// READ starts on a new line.
// Decision: a cursor over lines; next_record(n) reads up to n values from
// the next unread line on and says whether '/' ended it. Errors carry the
// file name and the line number. Not thread-safe (a cursor).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace acomms::gram {

// A file that cannot be imported; what() names the file, the line and why.
class ImportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ListValue {
  std::string text;     // the value, quotes removed
  bool quoted = false;  // written as a string
};

class ListDirectedReader {
 public:
  ListDirectedReader(std::string_view text, std::string file_name);

  struct Record {
    std::vector<ListValue> values;
    bool slash = false;  // ended by '/'
    std::size_t line = 0;
  };
  // Reads between `min` and `max` values; fewer than `min` is an error.
  // `what` names the record in errors.
  Record next_record(std::size_t min, std::size_t max, const std::string& what);
  bool at_end() const;

  double number(const ListValue& v, const std::string& what, std::size_t line) const;
  [[noreturn]] void fail(std::size_t line, const std::string& message) const;
  const std::string& file_name() const { return file_name_; }

 private:
  std::vector<std::string> lines_;
  std::size_t next_line_ = 0;
  std::string file_name_;
};

}  // namespace acomms::gram
