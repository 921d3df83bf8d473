#include "node/unheard_links.h"

#include <optional>

namespace acomms::node {

UnheardPackets::Hooks unheard_on_links(const std::vector<std::unique_ptr<NodeLink>>& links) {
  return UnheardPackets::Hooks{
      [&links](int32_t src) {
        uint64_t lost = 0;
        for (const auto& link : links) lost += link->controller().lost_recorded(src);
        return lost;
      },
      [&links](int32_t src) {
        NodeLink* heard_by = nullptr;
        double newest = 0;
        for (const auto& link : links) {
          std::optional<NodeLink::Heard> heard = link->last_heard(src);
          if (heard && (heard_by == nullptr || heard->time_s > newest)) {
            heard_by = link.get();
            newest = heard->time_s;
          }
        }
        if (heard_by != nullptr) heard_by->record_unheard(src);
      }};
}

}  // namespace acomms::node
