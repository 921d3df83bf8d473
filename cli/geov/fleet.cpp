#include "fleet.h"

#include <cmath>

#include "json_text.h"
#include "util/seconds.h"

namespace acomms::cli::geov {

std::string position_json(const telemetry::Position& p) {
  // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on
  // "literal" + std::string temporaries.
  std::string out = "[";
  out += json_number(p.time());
  out += ',';
  out += json_number(p.x());
  out += ',';
  out += json_number(p.y());
  out += ',';
  out += json_number(p.depth());
  out += ',';
  out += p.has_lat() ? json_number(p.lat()) : "null";
  out += ',';
  out += p.has_lon() ? json_number(p.lon()) : "null";
  out += ']';
  return out;
}

Fleet::Fleet(std::size_t max_positions_per_vehicle, std::size_t max_updates)
    : max_positions_(max_positions_per_vehicle),
      max_updates_(max_updates),
      // Milliseconds of the start: a restarted server has another epoch.
      epoch_(static_cast<uint64_t>(util::unix_seconds_now() * 1000)) {}

int Fleet::add_positions(const std::vector<telemetry::Position>& positions) {
  std::lock_guard lock(mutex_);
  std::map<int32_t, std::vector<telemetry::Position>> added;
  for (const telemetry::Position& p : positions) {
    if (!std::isfinite(p.time()) || !std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
    Vehicle& vehicle = vehicles_[p.src()];
    if (!vehicle.track.emplace(p.time(), p).second) continue;
    added[p.src()].push_back(p);
    if (vehicle.track.size() > max_positions_) vehicle.track.erase(vehicle.track.begin());
  }
  int count = 0;
  for (const auto& [src, list] : added) {
    publish(src, list);
    count += static_cast<int>(list.size());
  }
  return count;
}

void Fleet::heard(int32_t src, double time, const v1::LinkFigures* figures) {
  std::lock_guard lock(mutex_);
  Vehicle& vehicle = vehicles_[src];
  if (time <= vehicle.last_heard && !figures) return;  // nothing new to show
  vehicle.last_heard = std::max(vehicle.last_heard, time);
  if (figures) vehicle.link = *figures;
  publish(src, {});
}

void Fleet::set_queued(const std::string& daemon, std::map<int32_t, std::vector<QueuedToVehicle>> by_dest) {
  std::lock_guard lock(mutex_);
  std::map<int32_t, std::vector<QueuedToVehicle>>& old = queued_[daemon];
  std::set<int32_t> touched;
  for (const auto& [dest, list] : old) touched.insert(dest);
  for (const auto& [dest, list] : by_dest) touched.insert(dest);
  auto ids = [](const std::vector<QueuedToVehicle>& list) {
    std::vector<std::pair<int64_t, bool>> out;
    for (const auto& q : list) out.emplace_back(q.id, q.in_flight);
    return out;
  };
  std::set<int32_t> changed;
  for (int32_t dest : touched) {
    const auto a = old.count(dest) ? ids(old[dest]) : std::vector<std::pair<int64_t, bool>>{};
    const auto b = by_dest.count(dest) ? ids(by_dest[dest]) : std::vector<std::pair<int64_t, bool>>{};
    if (a != b) changed.insert(dest);
  }
  old = std::move(by_dest);
  for (int32_t dest : changed) {
    if (vehicles_.count(dest)) publish(dest, {});
  }
}

std::vector<QueuedToVehicle> Fleet::queued_to(int32_t src) const {
  std::vector<QueuedToVehicle> out;
  for (const auto& [daemon, by_dest] : queued_) {
    auto it = by_dest.find(src);
    if (it != by_dest.end()) out.insert(out.end(), it->second.begin(), it->second.end());
  }
  return out;
}

std::string Fleet::summary_json(int32_t src, const Vehicle& vehicle) const {
  std::string out = "\"src\":" + std::to_string(src) + ",\"positions\":" + std::to_string(vehicle.track.size());
  if (vehicle.track.empty()) {
    out += ",\"last\":null,\"heading\":null";
  } else {
    const telemetry::Position& last = vehicle.track.rbegin()->second;
    out += ",\"last\":" + position_json(last);
    // Heading over ground from the last two positions (degrees from north,
    // clockwise); the telemetry carries no heading of its own.
    std::string heading = "null";
    if (vehicle.track.size() >= 2) {
      const telemetry::Position& before = std::next(vehicle.track.rbegin())->second;
      const double dx = last.x() - before.x(), dy = last.y() - before.y();
      if (dx != 0 || dy != 0) heading = json_number(std::fmod(std::atan2(dx, dy) * 180 / M_PI + 360, 360));
    }
    out += ",\"heading\":" + heading;
  }
  out += ",\"last_heard\":" + json_number(vehicle.last_heard);
  if (vehicle.link) {
    const v1::LinkFigures& link = *vehicle.link;
    out += ",\"link\":{\"rate\":" + std::to_string(link.rate()) +
           ",\"snr_in_db\":" + (link.has_snr_in_db() ? json_number(link.snr_in_db()) : "null") +
           ",\"snr_out_db\":" + (link.has_snr_out_db() ? json_number(link.snr_out_db()) : "null") +
           ",\"quality\":" + json_string(link.link_quality()) + "}";
  } else {
    out += ",\"link\":null";
  }
  const std::vector<QueuedToVehicle> queued = queued_to(src);
  out += ",\"queued_count\":" + std::to_string(queued.size()) + ",\"queued\":[";
  for (std::size_t i = 0; i < queued.size() && i < 20; ++i) {
    if (i) out += ",";
    out += "{\"id\":" + std::to_string(queued[i].id) + ",\"type\":" + json_string(queued[i].type) +
           ",\"submitted_at\":" + json_number(queued[i].submitted_at) +
           ",\"in_flight\":" + (queued[i].in_flight ? "true" : "false") + "}";
  }
  return out + "]";
}

void Fleet::publish(int32_t src, const std::vector<telemetry::Position>& added) {
  std::string json = "{";
  json += summary_json(src, vehicles_.at(src));
  json += ",\"added\":[";
  for (std::size_t i = 0; i < added.size(); ++i) {
    if (i) json += ',';
    json += position_json(added[i]);
  }
  json += "]}";
  updates_.emplace_back(next_id_++, std::move(json));
  while (updates_.size() > max_updates_) updates_.pop_front();
  changed_.notify_all();
}

double Fleet::last_time(int32_t src) const {
  std::lock_guard lock(mutex_);
  auto it = vehicles_.find(src);
  return it == vehicles_.end() || it->second.track.empty() ? 0 : it->second.track.rbegin()->first;
}

std::optional<telemetry::Position> Fleet::last_position(int32_t src) const {
  std::lock_guard lock(mutex_);
  auto it = vehicles_.find(src);
  if (it == vehicles_.end() || it->second.track.empty()) return std::nullopt;
  return it->second.track.rbegin()->second;
}

std::optional<std::pair<double, double>> Fleet::span(std::optional<int32_t> src) const {
  std::lock_guard lock(mutex_);
  std::optional<std::pair<double, double>> out;
  for (const auto& [id, vehicle] : vehicles_) {
    if ((src && *src != id) || vehicle.track.empty()) continue;
    const double first = vehicle.track.begin()->first, last = vehicle.track.rbegin()->first;
    out = out ? std::pair{std::min(out->first, first), std::max(out->second, last)} : std::pair{first, last};
  }
  return out;
}

std::set<int32_t> Fleet::vehicles() const {
  std::lock_guard lock(mutex_);
  std::set<int32_t> out;
  for (const auto& [src, vehicle] : vehicles_) {
    if (!vehicle.track.empty()) out.insert(src);
  }
  return out;
}

bool Fleet::has_vehicle(int32_t src) const {
  std::lock_guard lock(mutex_);
  return vehicles_.count(src) != 0;
}

std::string Fleet::snapshot_json(double now) const {
  std::lock_guard lock(mutex_);
  std::string out = "{\"epoch\":" + std::to_string(epoch_) + ",\"id\":" + std::to_string(next_id_ - 1) +
                    ",\"now\":" + json_number(now) + ",\"vehicles\":[";
  bool first = true;
  for (const auto& [src, vehicle] : vehicles_) {
    out += first ? "{" : ",{";
    out += summary_json(src, vehicle);
    out += ",\"track\":[";
    first = false;
    bool first_position = true;
    for (const auto& [time, p] : vehicle.track) {
      if (!first_position) out += ',';
      out += position_json(p);
      first_position = false;
    }
    out += "]}";
  }
  return out + "]}";
}

std::map<int32_t, std::vector<telemetry::Position>> Fleet::history(double from, double to,
                                                                    std::optional<int32_t> src) const {
  std::lock_guard lock(mutex_);
  std::map<int32_t, std::vector<telemetry::Position>> out;
  for (const auto& [id, vehicle] : vehicles_) {
    if (src && *src != id) continue;
    auto& list = out[id];
    for (auto it = vehicle.track.lower_bound(from); it != vehicle.track.end() && it->first <= to; ++it) {
      list.push_back(it->second);
    }
  }
  return out;
}

FleetUpdates Fleet::updates_after(uint64_t epoch, uint64_t after, std::chrono::milliseconds wait) const {
  std::unique_lock lock(mutex_);
  FleetUpdates out;
  if (epoch != epoch_ || after >= next_id_ || (after + 1 < next_id_ && (updates_.empty() || updates_.front().first > after + 1))) {
    out.reset = true;
    return out;
  }
  changed_.wait_for(lock, wait, [&] { return closed_ || next_id_ - 1 > after; });
  out.closed = closed_;
  for (const auto& update : updates_) {
    if (update.first > after) out.events.push_back(update);
  }
  return out;
}

uint64_t Fleet::last_update_id() const {
  std::lock_guard lock(mutex_);
  return next_id_ - 1;
}

void Fleet::close() {
  std::lock_guard lock(mutex_);
  closed_ = true;
  changed_.notify_all();
}

}  // namespace acomms::cli::geov
