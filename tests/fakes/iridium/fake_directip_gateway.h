#pragma once
// A fake Iridium gateway's DirectIP side (../shared/spec/iridium-sbd.md §9),
// for the shore endpoint's tests and for a whole vehicle-to-shore run with
// the fake 9603 (sbd_gateway.h is the seam the modem calls).
//
// MO: each MO a session delivered (mo_received) is pushed to the shore's MO
// server, one TCP connection per MO, in order, as the real gateway does:
// connect, send the message, then wait for the shore to close (or, with
// expect_mo_confirmation, for the 7-byte confirmation `01 00 04 05 00 01
// 01`). A delivery that fails (no listener, a reset, no confirmation) is
// retried after mo_retry (the real schedule is 1, 5, 10, ... s: spec §9.2;
// tests shorten it), so an MO is never dropped while the fake lives.
//
// MT: a server on mt_port() takes one MT per connection, answers the MT
// confirmation with the spec's statuses (§9.3.4: position in queue, or −1
// IMEI malformed, −3 payload too big, −4 no payload, −5 queue full (50),
// −7 wrong lengths), and queues accepted payloads per IMEI for take_mt. With
// the assign-MTMSN flag the client id is the MTMSN; otherwise the fake
// numbers MTs itself.
//
// The byte layouts are written out here by hand, not with the shore's
// codec: a mistake in one is then not repeated in the other.
//
// Faults: set_shore_reachable(false) (no connection is attempted: "no route
// to the shore"); push_raw_mo (one connection with arbitrary bytes: wrong
// lengths, oversize, unknown IEIs); open_hanging_mo (sends some bytes and
// then nothing); refuse_next_mt, hang_next_mt and
// garble_next_mt_confirmation on the MT side.
//
// Thread-safety: every member may be called from any thread; the fake runs
// its sockets on a thread of its own.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sbd_gateway.h"

namespace acomms::fake_iridium {

class FakeDirectIpGateway : public SbdGateway {
 public:
  struct Options {
    std::string shore_mo_address = "127.0.0.1:10800";  // the shore's MO server, host:port
    std::chrono::milliseconds mo_retry{200};
    bool expect_mo_confirmation = false;
    // How long a push waits for the shore's close (or confirmation).
    std::chrono::milliseconds mo_answer_timeout{5000};
  };
  // One MT as the fake received it, with the status it answered.
  struct MtSubmission {
    uint32_t client_id = 0;
    std::string imei;
    uint16_t flags = 0;
    std::string payload;
    int16_t status = 0;
    bool answered = true;  // false: hang_next_mt or garble_next_mt_confirmation (status meaningless)
  };

  explicit FakeDirectIpGateway(Options options);
  ~FakeDirectIpGateway() override;  // stops the thread; undelivered MOs are dropped

  // SbdGateway.
  void mo_received(const std::string& imei, uint16_t momsn, const std::string& payload) override;
  std::optional<MtMessage> take_mt(const std::string& imei) override;
  int mt_queued(const std::string& imei) const override;

  uint16_t mt_port() const;
  std::string mt_address() const { return "127.0.0.1:" + std::to_string(mt_port()); }

  // MOs waiting to be delivered (including one being pushed now).
  size_t mo_pending() const;
  // Pushes the shore completed (counted once per MO).
  size_t mo_delivered() const;
  // Connections attempted for MOs, failed ones included.
  size_t mo_attempts() const;
  // MT submissions received, in order.
  std::vector<MtSubmission> mt_submissions() const;

  // Faults.
  void set_shore_reachable(bool reachable);
  // One connection that sends `bytes` as they are, waits for the shore to
  // close it, and is not retried.
  void push_raw_mo(std::string bytes);
  // One connection that sends `bytes` and then nothing, held open until the
  // shore closes it; true once it has.
  void open_hanging_mo(std::string bytes);
  size_t hanging_closed_by_shore() const;
  // The next MT is answered with `status` (negative) and not queued.
  void refuse_next_mt(int16_t status);
  // The next MT connection is read and never answered (held open).
  void hang_next_mt();
  // The next MT is answered with a confirmation IE of 2 bytes, not 25
  // (a wrong length), and not queued.
  void garble_next_mt_confirmation();

  // The MO bytes for (imei, momsn, payload), as this fake pushes them:
  // header (CDR, IMEI, status 0, MOMSN, MTMSN 0, time) and payload IEs.
  static std::string mo_message(const std::string& imei, uint16_t momsn, const std::string& payload,
                                uint32_t cdr = 1, uint32_t time = 1700000000);

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace acomms::fake_iridium
