#pragma once
// What the map shows: every vehicle's track, link figures and the messages
// queued to it, gathered from one or more daemons, and the numbered stream
// of changes the pages follow.
//
// Why one numbered stream: a page that reconnects (its network blinked, the
// server restarted) says the last update it applied ("EPOCH:ID", the
// server-sent events' Last-Event-ID) and gets every later one, so it never
// misses a position. The ring holds the last max_updates; a page further
// behind, or one from an earlier server (another epoch), is told to reload
// the snapshot instead, which is complete because every position is kept.
//
// Positions are keyed by (vehicle, sample time): the same position from a
// live subscription, a Track back-fill and a second daemon is stored once.
//
// Thread-safety: every member may be called from any thread (one mutex).

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "acomms/telemetry/position.pb.h"
#include "acomms/v1/link_figures.pb.h"

namespace acomms::cli::geov {

struct QueuedToVehicle {
  int64_t id = 0;
  std::string type;
  double submitted_at = 0;
  bool in_flight = false;
};

struct FleetUpdates {
  bool reset = false;   // `after` is not in the ring: reload the snapshot
  bool closed = false;  // the server is stopping
  std::vector<std::pair<uint64_t, std::string>> events;  // id, JSON
};

class Fleet {
 public:
  explicit Fleet(std::size_t max_positions_per_vehicle = 500000, std::size_t max_updates = 20000);

  // Returns how many were new.
  int add_positions(const std::vector<telemetry::Position>& positions);
  // A message from `src` reached a daemon, with the modem's figures (null:
  // none came with it; the last ones are kept).
  void heard(int32_t src, double time, const v1::LinkFigures* figures);
  // What `daemon` has queued, by destination (replaces its previous list).
  void set_queued(const std::string& daemon, std::map<int32_t, std::vector<QueuedToVehicle>> by_dest);

  double last_time(int32_t src) const;  // 0: no position yet
  std::optional<telemetry::Position> last_position(int32_t src) const;
  // The times of the first and last position held (of every vehicle, or of
  // `src`); none without positions.
  std::optional<std::pair<double, double>> span(std::optional<int32_t> src = std::nullopt) const;
  std::set<int32_t> vehicles() const;   // those with a position
  bool has_vehicle(int32_t src) const;

  uint64_t epoch() const { return epoch_; }
  // {"epoch":E,"id":N,"now":T,"vehicles":[{summary..., "track":[[t,x,y,depth,lat,lon],...]}]}
  std::string snapshot_json(double now) const;
  // Positions with from <= time <= to; every vehicle, or only `src`.
  std::map<int32_t, std::vector<telemetry::Position>> history(double from, double to,
                                                               std::optional<int32_t> src = std::nullopt) const;

  // Updates after id `after` of epoch `epoch`; waits up to `wait` when there
  // is none yet.
  FleetUpdates updates_after(uint64_t epoch, uint64_t after, std::chrono::milliseconds wait) const;
  uint64_t last_update_id() const;
  // Wakes every waiting stream, which then ends.
  void close();

 private:
  struct Vehicle {
    std::map<double, telemetry::Position> track;
    std::optional<v1::LinkFigures> link;
    double last_heard = 0;
  };
  // REQUIRES: mutex_ held.
  std::string summary_json(int32_t src, const Vehicle& vehicle) const;
  void publish(int32_t src, const std::vector<telemetry::Position>& added);
  std::vector<QueuedToVehicle> queued_to(int32_t src) const;

  const std::size_t max_positions_;
  const std::size_t max_updates_;
  const uint64_t epoch_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::map<int32_t, Vehicle> vehicles_;
  std::map<std::string, std::map<int32_t, std::vector<QueuedToVehicle>>> queued_;
  std::deque<std::pair<uint64_t, std::string>> updates_;
  uint64_t next_id_ = 1;
  bool closed_ = false;
};

// "[t,x,y,depth,lat,lon]" (lat and lon null without a datum).
std::string position_json(const telemetry::Position& p);

}  // namespace acomms::cli::geov
