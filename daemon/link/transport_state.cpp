#include "link/transport_state.h"

namespace acomms::link {

const char* to_string(TransportState state) {
  switch (state) {
    case TransportState::kClosed: return "closed";
    case TransportState::kOpening: return "opening";
    case TransportState::kOpen: return "open";
    case TransportState::kWaiting: return "waiting";
  }
  return "unknown";
}

}  // namespace acomms::link
