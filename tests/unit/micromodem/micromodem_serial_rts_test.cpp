// RTS on a Micro-Modem's serial port (spec §1, §10 quirk 12): Linux asserts
// RTS when a tty opens and an MM2 then garbles its output, so the driver's
// port de-asserts it (TIOCMBIC, TIOCM_RTS) on the port's own descriptor as
// part of opening it, before the port is reported open.
//
// A pseudo-terminal has no modem control lines (the kernel answers ENOTTY),
// so what is checked is the call itself: this executable defines ioctl(),
// which the link library's call binds to, records each call and passes it
// on to the kernel. The port must still open and carry bytes when the line
// cannot be changed, as on a pty.

#include <gtest/gtest.h>

#include <asio/io_context.hpp>
#include <fcntl.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdarg>
#include <mutex>
#include <string>
#include <vector>

#include "link/serial_transport.h"
#include "micromodem/modem_port.h"

namespace {

struct IoctlCall {
  int fd;
  unsigned long request;
  int bits;  // *arg for the modem-line requests, else 0
};

std::mutex calls_mutex;
std::vector<IoctlCall> calls;

}  // namespace

extern "C" int ioctl(int fd, unsigned long request, ...) noexcept {
  va_list args;
  va_start(args, request);
  void* arg = va_arg(args, void*);
  va_end(args);
  int bits = 0;
  if ((request == TIOCMBIC || request == TIOCMBIS || request == TIOCMSET) && arg != nullptr) {
    bits = *static_cast<int*>(arg);
  }
  {
    std::lock_guard lock(calls_mutex);
    calls.push_back({fd, request, bits});
  }
  return static_cast<int>(::syscall(SYS_ioctl, fd, request, arg));
}

namespace acomms::drivers::micromodem {
namespace {

struct Pty {
  Pty() {
    char name[128];
    if (openpty(&master, &slave, name, nullptr, nullptr) != 0) return;
    path = name;
    fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
  }
  ~Pty() {
    if (master >= 0) ::close(master);
    if (slave >= 0) ::close(slave);
  }
  int master = -1, slave = -1;
  std::string path;
};

// The TIOCMBIC calls made on a descriptor of `device` while open() ran.
std::vector<IoctlCall> rts_clears_on(const std::string& device, const std::vector<IoctlCall>& made) {
  struct stat wanted {};
  if (::stat(device.c_str(), &wanted) != 0) return {};
  std::vector<IoctlCall> out;
  for (const IoctlCall& call : made) {
    struct stat seen {};
    if (call.request == TIOCMBIC && ::fstat(call.fd, &seen) == 0 && seen.st_rdev == wanted.st_rdev) {
      out.push_back(call);
    }
  }
  return out;
}

std::vector<IoctlCall> calls_during(const std::function<void()>& action) {
  {
    std::lock_guard lock(calls_mutex);
    calls.clear();
  }
  action();
  std::lock_guard lock(calls_mutex);
  return calls;
}

TEST(MicroModemSerialRtsTest, TheModemsSerialPortDeassertsRtsAsItOpensAndStillCarriesBytes) {
  Pty pty;
  ASSERT_FALSE(pty.path.empty()) << "openpty failed";
  asio::io_context io;
  std::unique_ptr<ModemPort> port = transport_port(pty.path, 19200, io);
  bool open = false;
  std::string received;
  std::vector<IoctlCall> made = calls_during([&] {
    port->open([&](std::string_view bytes) { received += bytes; },
               [&](link::TransportState state, const std::string&) { open = state == link::TransportState::kOpen; });
  });
  ASSERT_TRUE(open) << "the port did not open at once";
  std::vector<IoctlCall> clears = rts_clears_on(pty.path, made);
  ASSERT_EQ(clears.size(), 1u) << "expected one TIOCMBIC on " << pty.path << " while opening";
  EXPECT_EQ(clears[0].bits, TIOCM_RTS) << "only RTS is de-asserted (DTR and the rest are left)";

  // The pty refused the ioctl (no modem lines); the port works regardless.
  ASSERT_EQ(::write(pty.master, "$CAREV,000052,AUV,0.93.0.09*07\r\n", 32), 32);
  for (int i = 0; i < 200 && received.size() < 32; ++i) io.run_for(std::chrono::milliseconds(10));
  EXPECT_EQ(received, "$CAREV,000052,AUV,0.93.0.09*07\r\n");
  port->close();
}

TEST(MicroModemSerialRtsTest, APlainSerialTransportLeavesTheModemLinesAlone) {
  Pty pty;
  ASSERT_FALSE(pty.path.empty()) << "openpty failed";
  asio::io_context io;
  link::SerialTransport transport(io, link::SerialSettings{pty.path, 19200});
  std::vector<IoctlCall> made = calls_during([&] { transport.open([](std::string_view) {}, nullptr); });
  ASSERT_EQ(transport.state(), link::TransportState::kOpen);
  EXPECT_TRUE(rts_clears_on(pty.path, made).empty());
  transport.close();
}

TEST(MicroModemSerialRtsTest, ATcpPortHasNoRtsToClear) {
  asio::io_context io;
  std::unique_ptr<ModemPort> port = transport_port("tcp:127.0.0.1:9", 0, io);
  std::vector<IoctlCall> made = calls_during([&] { port->open([](std::string_view) {}, nullptr); });
  for (const IoctlCall& call : made) EXPECT_NE(call.request, static_cast<unsigned long>(TIOCMBIC));
  port->close();
}

}  // namespace
}  // namespace acomms::drivers::micromodem
