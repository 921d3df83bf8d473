#pragma once
// The dynamic priority of a queue (Schneider (2013), section 2.3):
//
//   P(t) = value_base * (t - t_last_sent) / ttl
//
// A queue's claim on the link grows the longer it has gone without sending,
// at a rate set by how valuable its messages are (value_base) and how soon
// they go stale (ttl). Every queue therefore gets the link eventually, and a
// queue that just sent falls back to zero. Ties go to the queue that sent
// longest ago.
//
// Thread-safe: a pure function.

namespace acomms::queue {

inline double dynamic_priority(double value_base, double ttl_s, double seconds_since_last_sent) {
  return value_base * seconds_since_last_sent / ttl_s;
}

}  // namespace acomms::queue
