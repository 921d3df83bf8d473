#pragma once
#include <stdexcept>
#include <string>

namespace acomms::store {

// Any failure of the store: the message says which file and what to do.
class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace acomms::store
