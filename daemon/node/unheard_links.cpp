#include "node/unheard_links.h"

#include <algorithm>
#include <optional>
#include <vector>

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
      },
      [&links](int32_t src) {
        // The link that delivered the message after the gap heard the
        // sender last; another within the window makes it several.
        std::vector<double> times;
        for (const auto& link : links) {
          if (std::optional<NodeLink::Heard> heard = link->last_heard(src)) times.push_back(heard->time_s);
        }
        if (times.size() < 2) return false;
        std::sort(times.begin(), times.end());
        return times[times.size() - 1] - times[times.size() - 2] <= UnheardPackets::kSeveralLinks_s;
      }};
}

}  // namespace acomms::node
