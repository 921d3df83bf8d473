#include "line_console.h"

#include <sstream>

namespace acomms::fake_micromodem {

namespace {

constexpr auto kNoiseTick = std::chrono::milliseconds(50);
constexpr double kFullLineBytesPerSecond = 1920;  // 19200 baud, 10 bits a byte

}  // namespace

LineConsole::LineConsole(asio::io_context& context, std::map<int, FakeMicroModem*> modems,
                         std::map<int, TcpPort*> tcp_ports)
    : context_(context), modems_(std::move(modems)), tcp_ports_(std::move(tcp_ports)) {}

std::optional<std::string> LineConsole::run(const std::string& line) {
  std::istringstream in(line);
  int address = -1;
  std::string command;
  if (!(in >> address >> command)) return std::nullopt;
  if (command != "unplug" && command != "plug" && command != "noise-for") return std::nullopt;
  if (command == "noise-for") {
    auto modem = modems_.find(address);
    if (modem == modems_.end()) return "no fake modem with address " + std::to_string(address);
    double seconds = 0, rate = kFullLineBytesPerSecond;
    if (!(in >> seconds) || !(seconds > 0) || seconds > 3600) return "usage: <address> noise-for <seconds> [bytes/s]";
    if (in >> rate && !(rate >= 20 && rate <= 1e7)) return "noise-for: bytes/s must be in 20..10000000";
    auto until = std::chrono::steady_clock::now() +
                 std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
    size_t chunk = static_cast<size_t>(rate * std::chrono::duration<double>(kNoiseTick).count());
    noise(*modem->second, until, chunk, std::make_shared<asio::steady_timer>(context_));
    return "ok";
  }
  auto port = tcp_ports_.find(address);
  if (port == tcp_ports_.end()) return "no fake modem on TCP with address " + std::to_string(address);
  if (command == "unplug") {
    port->second->unplug();
  } else {
    port->second->plug();
  }
  return "ok";
}

void LineConsole::noise(FakeMicroModem& modem, std::chrono::steady_clock::time_point until, size_t chunk,
                        std::shared_ptr<asio::steady_timer> timer) {
  if (std::chrono::steady_clock::now() >= until) return;
  modem.write_raw(modem.faults().noise_burst(chunk));
  timer->expires_after(kNoiseTick);
  timer->async_wait([this, &modem, until, chunk, timer](const std::error_code& error) {
    if (!error) noise(modem, until, chunk, timer);
  });
}

}  // namespace acomms::fake_micromodem
