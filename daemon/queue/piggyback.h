#pragma once
// A node's own few bytes that ride in a frame's spare space: the seam
// through which a layer above the queues (node/consistency_watch.h: the
// fleet-consistency announce) sends and hears a small control message
// without being a queue.
//
// Why not a queue of its own: a queued message contests places in a frame
// (frame_building.cpp) and, winning, takes one from real traffic; it is
// journaled and acknowledged. A piggyback is none of that. It is asked for
// only after the contest of the transmission's last frame has placed every
// message that fits, and goes only into what is left of that frame (or a
// frame no message wanted): by construction it never displaces, delays or
// splits a queued message, and a frame of its own goes only in a
// transmission that goes anyway (DataRequest::in_slot): it never makes a
// satellite modem open a session. It is the last thing in its frame, so a
// receiver that does not know its id (a frame is DCCL messages back to back
// and an unknown id ends it) loses nothing the frame carried before it.
//
// On the receive side, bytes that begin with the piggyback's DCCL id header
// are handed to it before any type is looked up; it says how many bytes it
// used (0: malformed, which ends the frame as undecodable bytes do).
//
// Threads: every call comes from the core thread (QueueManager's).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace acomms::queue {

class Piggyback {
 public:
  virtual ~Piggyback() = default;

  // The DCCL id whose header marks the piggyback in a frame (128..32767).
  virtual uint32_t dccl_id() const = 0;

  // The bytes to append on link `link` now, given `room` bytes free at the
  // end of a frame; empty: nothing (not due, or it does not fit). A
  // non-empty answer counts as sent.
  virtual std::string take(int link, size_t room, double now) = 0;

  // The piggyback at the start of `rest`, heard from `src` on `link`.
  // Returns the bytes it used; 0 when they do not decode.
  virtual size_t on_received(std::string_view rest, int32_t src, int link, double now) = 0;
};

}  // namespace acomms::queue
