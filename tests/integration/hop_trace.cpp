#include "hop_trace.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <regex>

#include "daemon_harness.h"

namespace acomms::testing {

using namespace std::chrono_literals;

namespace {

constexpr const char* kCustodyPrefix = "acomms.route.Custody.";

std::optional<double> queued_at(const std::vector<v1::Event>& events, int64_t id) {
  for (const v1::Event& e : events) {
    if (e.kind() == "queued" && e.message_id() == id) return e.time();
  }
  return std::nullopt;
}

}  // namespace

CustodyWatch::CustodyWatch(std::map<int, std::string> relays) : relays_(std::move(relays)) {
  thread_ = std::thread([this] {
    while (running_) {
      poll_once();
      std::this_thread::sleep_for(50ms);
    }
  });
}

CustodyWatch::~CustodyWatch() {
  running_ = false;
  thread_.join();
}

void CustodyWatch::poll_once() {
  static const std::regex head(
      R"re("origin":(\d+),"destination":(\d+),"seq":(\d+),"hops":(\d+))re");
  for (const auto& [node, socket] : relays_) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + 1s);
    v1::ListQueuedRequest request;
    request.set_limit(10000);
    v1::ListQueuedResponse response;
    if (!api(socket)->ListQueued(&context, request, &response).ok()) continue;  // e.g. the buoy is down
    std::lock_guard lock(mutex_);
    for (const v1::QueuedMessage& m : response.messages()) {
      std::smatch match;
      if (m.type().rfind(kCustodyPrefix, 0) != 0 || !std::regex_search(m.json(), match, head)) continue;
      seen_.try_emplace({node, m.message_id()},
                        CustodySighting{node, m.message_id(), std::stoi(match[1]), std::stoi(match[2]),
                                        std::stoi(match[3]), std::stoi(match[4])});
    }
  }
}

std::vector<CustodySighting> CustodyWatch::sightings() const {
  std::lock_guard lock(mutex_);
  std::vector<CustodySighting> out;
  for (const auto& [key, s] : seen_) out.push_back(s);
  return out;
}

std::vector<v1::Event> node_events(const std::string& socket, const std::vector<std::string>& kinds) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + 10s);
  v1::EventsRequest request;
  for (const std::string& kind : kinds) request.add_kinds(kind);
  request.set_limit(10000);
  v1::EventsResponse response;
  grpc::Status status = api(socket)->Events(&context, request, &response);
  if (!status.ok()) return {};
  return {response.events().begin(), response.events().end()};
}

std::vector<v1::Event> message_history(const std::string& socket, int64_t message_id) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + 10s);
  v1::EventsRequest request;
  request.set_message_id(message_id);
  v1::EventsResponse response;
  if (!api(socket)->Events(&context, request, &response).ok()) return {};
  return {response.events().begin(), response.events().end()};
}

NetworkFigures network_figures(const std::vector<TracedMessage>& messages,
                               const std::vector<CustodySighting>& sightings,
                               const std::map<int, std::vector<v1::Event>>& events) {
  NetworkFigures f;
  for (const auto& [node, list] : events) {
    for (const v1::Event& e : list) {
      f.sent_events += e.kind() == "sent";
      f.retries += e.kind() == "retry";
      f.hop_acks += e.kind() == "acked";
      f.end_to_end_acks += e.kind() == "delivered";
    }
  }
  for (const auto& [node, list] : events) {
    std::map<int64_t, double> taken;
    for (const v1::Event& e : list) {
      if (e.type().rfind(kCustodyPrefix, 0) != 0) continue;
      if (e.kind() == "queued") taken.emplace(e.message_id(), e.time());
      auto it = taken.find(e.message_id());
      if (e.kind() != "sent" || it == taken.end()) continue;
      HopDelay& d = f.relay_wait[node];
      const double s = e.time() - it->second;
      if (s > d.max_s) f.relay_worst_id[node] = e.message_id();
      ++d.n, d.sum_s += s, d.max_s = std::max(d.max_s, s);
      taken.erase(it);  // the first send only
    }
  }
  for (const TracedMessage& m : messages) {
    ++f.messages;
    if (m.delivered_at == 0) continue;
    ++f.delivered;
    const auto origin_queued = queued_at(events.at(m.origin), m.origin_id);
    if (!origin_queued) continue;
    f.end_to_end_s.push_back(m.delivered_at - *origin_queued);
    // When it entered each node of its path.
    std::vector<double> entered{*origin_queued};
    for (size_t i = 1; i + 1 < m.path.size(); ++i) {
      std::optional<int64_t> local;
      for (const CustodySighting& s : sightings) {
        if (s.node == m.path[i] && s.origin == m.origin && s.destination == m.destination &&
            s.seq == static_cast<int>(m.origin_id & 0xffff) && (!local || s.local_id < *local)) {
          local = s.local_id;
        }
      }
      std::optional<double> at = local ? queued_at(events.at(m.path[i]), *local) : std::nullopt;
      if (!at) break;
      entered.push_back(*at);
    }
    if (entered.size() + 1 != m.path.size()) continue;  // a hop not seen: not traced
    entered.push_back(m.delivered_at);
    ++f.traced;
    for (size_t i = 0; i + 1 < entered.size(); ++i) {
      HopDelay& d = f.per_hop[{m.path[i], m.path[i + 1]}];
      const double s = entered[i + 1] - entered[i];
      ++d.n, d.sum_s += s, d.max_s = std::max(d.max_s, s);
      ++f.hops;
    }
  }
  return f;
}

void NetworkFigures::print(std::ostream& out, const std::map<int, std::string>& names) const {
  char line[256];
  out << "gateway fleet figures:\n";
  std::snprintf(line, sizeof line,
                "  messages %d, delivered %d (traced hop by hop: %d, %d hops, %.2f hops each)\n", messages, delivered,
                traced, hops, traced ? static_cast<double>(hops) / traced : 0.0);
  out << line;
  std::snprintf(line, sizeof line,
                "  on the air: %llu sends (each try of each hop), %llu retries; hop acks %llu; end-to-end acks "
                "%llu\n",
                static_cast<unsigned long long>(sent_events), static_cast<unsigned long long>(retries),
                static_cast<unsigned long long>(hop_acks), static_cast<unsigned long long>(end_to_end_acks));
  out << line;
  for (const auto& [hop, d] : per_hop) {
    std::snprintf(line, sizeof line, "  hop %-9s -> %-9s  %3d messages, delay mean %6.2f s, max %6.2f s\n",
                  names.at(hop.first).c_str(), names.at(hop.second).c_str(), d.n, d.sum_s / d.n, d.max_s);
    out << line;
  }
  for (const auto& [node, d] : relay_wait) {
    std::snprintf(line, sizeof line, "  held at %-9s before the first send on: %3d messages, mean %6.2f s, max %6.2f s\n",
                  names.at(node).c_str(), d.n, d.sum_s / d.n, d.max_s);
    out << line;
  }
  if (!end_to_end_s.empty()) {
    const double sum = std::accumulate(end_to_end_s.begin(), end_to_end_s.end(), 0.0);
    std::snprintf(line, sizeof line, "  end to end: mean %.2f s, max %.2f s\n", sum / end_to_end_s.size(),
                  *std::max_element(end_to_end_s.begin(), end_to_end_s.end()));
    out << line;
  }
}

}  // namespace acomms::testing
