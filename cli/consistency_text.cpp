#include "consistency_text.h"

#include <cstdio>
#include <ctime>

namespace acomms::cli {
namespace {

std::string utc(double unix_s) {
  const std::time_t t = static_cast<std::time_t>(unix_s);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

void print_consistency(const std::string& indent, const std::string& own,
                       const google::protobuf::RepeatedPtrField<v1::NodeConsistency>& nodes, double now_s) {
  if (own.empty()) return;
  std::printf("%sconsistency:  digest %s\n", indent.c_str(), own.c_str());
  for (const v1::NodeConsistency& node : nodes) {
    std::printf("%s  node %-5d %s on %s: %s, heard %.0f s ago (%llu announce(s))", indent.c_str(), node.node(),
                node.digest().c_str(), node.link().c_str(), node.agrees() ? "agrees" : "DISAGREES",
                now_s - node.last_heard(), static_cast<unsigned long long>(node.announces()));
    if (!node.agrees()) std::printf(", since %s", utc(node.disagrees_since()).c_str());
    std::printf("\n");
  }
}

}  // namespace acomms::cli
