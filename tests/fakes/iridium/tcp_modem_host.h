#pragma once
// The fake 9603 on a TCP port, as a modem behind a serial-to-TCP gateway
// looks to the driver ("tcp:127.0.0.1:PORT"): for tests that run a real
// acommsd against it. The modem, its scheduler (real time) and the socket
// live on one thread of their own; the test reaches the modem only through
// call(), which runs on that thread and waits. The gateway is the caller's
// (InMemorySbdGateway is thread-safe).
//
// One connection at a time: a new one replaces the old (a daemon that
// restarts its driver reconnects).
//
// Thread-safety: every public member may be called from any thread.

#include <functional>
#include <memory>
#include <string>

#include "fake_sbd_modem.h"
#include "sbd_gateway.h"

namespace acomms::fake_iridium {

class TcpModemHost {
 public:
  // Listens on 127.0.0.1 at an ephemeral port; the modem starts powered.
  TcpModemHost(SbdGateway& gateway, FakeSbdConfig config);
  ~TcpModemHost();
  TcpModemHost(const TcpModemHost&) = delete;
  TcpModemHost& operator=(const TcpModemHost&) = delete;

  int port() const;
  // Runs `work` on the modem's thread and returns when it has run.
  void call(const std::function<void(FakeSbdModem& modem)>& work);
  std::string transcript();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace acomms::fake_iridium
