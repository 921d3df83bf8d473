// fake_micromodem: fake WHOI Micro-Modems on pseudo-terminals or TCP ports,
// sharing one simulated water (and, with --bus-port/--bus-peer, the water
// of other fake_micromodem processes). For driver and daemon tests without
// hardware. Prints one line per modem, then reads fault commands on stdin
// (fault_console.h):
//   modem 1 mm2 pty /dev/pts/7
//   modem 2 mm1 tcp 127.0.0.1:40002
// Example: two modems 1.5 km apart, ten times faster than real time:
//   fake_micromodem --modem 1,mm2,0,0,0 --modem 2,mm2,1500,0,0 --time-scale 10

#include <CLI/CLI.hpp>
#include <asio/io_context.hpp>
#include <asio/posix/stream_descriptor.hpp>
#include <asio/read_until.hpp>
#include <asio/signal_set.hpp>
#include <asio/streambuf.hpp>

#include <unistd.h>

#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "fake_micromodem.h"
#include "fault_console.h"
#include "host_ports.h"
#include "line_console.h"
#include "scaled_scheduler.h"
#include "udp_water_bus.h"

using namespace acomms::fake_micromodem;

namespace {

// "1,mm2,0,0,0" → address, generation, position.
FakeModemConfig parse_modem(const std::string& text) {
  std::istringstream in(text);
  std::string address, generation, x, y, z;
  std::getline(in, address, ',');
  std::getline(in, generation, ',');
  std::getline(in, x, ',');
  std::getline(in, y, ',');
  std::getline(in, z, ',');
  FakeModemConfig config;
  try {
    config.address = std::stoi(address);
    config.position = {x.empty() ? 0 : std::stod(x), y.empty() ? 0 : std::stod(y), z.empty() ? 0 : std::stod(z)};
  } catch (const std::exception&) {
    throw CLI::ValidationError("--modem", "'" + text + "' is not ADDRESS,mm1|mm2,X,Y,Z");
  }
  if (config.address < 1 || config.address > 127) {
    throw CLI::ValidationError("--modem", "address " + address + " is outside 1..127");
  }
  if (generation != "mm1" && generation != "mm2") {
    throw CLI::ValidationError("--modem", "generation '" + generation + "' is not mm1 or mm2");
  }
  config.generation = generation == "mm1" ? Generation::kMM1 : Generation::kMM2;
  return config;
}

// "nb,26000,X,Y,Z[,silent]" or "remus,A,X,Y,Z[,silent]" → an LBL transponder.
Transponder parse_transponder(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> parts;
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  auto bad = [&] {
    return CLI::ValidationError("--transponder", "'" + text + "' is not nb,FREQ_HZ,X,Y,Z[,silent] or remus,A..D,X,Y,Z[,silent]");
  };
  if (parts.size() < 5 || parts.size() > 6 || (parts.size() == 6 && parts[5] != "silent")) throw bad();
  Transponder t;
  try {
    if (parts[0] == "nb") {
      t.kind = Transponder::Kind::kNarrowband;
      t.reply_frequency_hz = std::stoi(parts[1]);
    } else if (parts[0] == "remus" && parts[1].size() == 1 && parts[1][0] >= 'A' && parts[1][0] <= 'D') {
      t.kind = Transponder::Kind::kRemus;
      t.beacon = parts[1][0];
    } else {
      throw bad();
    }
    t.position = {std::stod(parts[2]), std::stod(parts[3]), std::stod(parts[4])};
  } catch (const std::logic_error&) {
    throw bad();
  }
  t.answers = parts.size() == 5;
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Fake WHOI Micro-Modems sharing a simulated water"};
  std::vector<std::string> modem_specs;
  std::string transport = "pty";
  uint16_t tcp_base_port = 0;
  double time_scale = 1, sound_speed = 1500, loss = 0, frame_errors = 0, header_errors = 0;
  uint32_t seed = 1;
  uint16_t bus_port = 0;
  std::vector<uint16_t> bus_peers;
  app.add_option("--modem", modem_specs, "ADDRESS,mm1|mm2,X,Y,Z (metres); repeatable")->required();
  std::vector<std::string> transponder_specs;
  app.add_option("--transponder", transponder_specs,
                 "LBL transponder: nb,FREQ_HZ,X,Y,Z or remus,A..D,X,Y,Z; ',silent' at the end: never answers; repeatable");
  app.add_option("--transport", transport, "pty or tcp")->check(CLI::IsMember({"pty", "tcp"}));
  app.add_option("--tcp-base-port", tcp_base_port, "modem i listens on base+i (0: any free port)");
  app.add_option("--time-scale", time_scale, "simulated seconds per real second")->check(CLI::Range(0.01, 1000.0));
  app.add_option("--sound-speed", sound_speed, "m/s")->check(CLI::Range(100.0, 5000.0));
  app.add_option("--loss", loss, "probability that a receiver misses a packet")->check(CLI::Range(0.0, 1.0));
  app.add_option("--frame-errors", frame_errors, "probability of $CAMSG,BAD_CRC per frame")->check(CLI::Range(0.0, 1.0));
  app.add_option("--header-errors", header_errors,
                 "probability that a PSK data packet's header does not decode ($CACST mode 1, PSK error 1)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--seed", seed, "random seed (losses, frame errors, noise)");
  app.add_option("--bus-port", bus_port, "UDP port on 127.0.0.1 joining other processes' water");
  app.add_option("--bus-peer", bus_peers, "another process's --bus-port; repeatable");
  CLI11_PARSE(app, argc, argv);

  asio::io_context context;
  ScaledScheduler scheduler(context, time_scale);
  Water::Settings water_settings{sound_speed, loss, seed, {}};
  try {
    for (const std::string& spec : transponder_specs) water_settings.transponders.push_back(parse_transponder(spec));
  } catch (const CLI::Error& e) {
    return app.exit(e);
  }
  Water water(scheduler, water_settings);
  std::unique_ptr<UdpWaterBus> bus;
  if (bus_port != 0) bus = std::make_unique<UdpWaterBus>(context, water, bus_port, bus_peers);

  std::vector<std::unique_ptr<FakeMicroModem>> modems;
  std::vector<std::unique_ptr<PtyPort>> ptys;
  std::vector<std::unique_ptr<TcpPort>> tcps;
  std::map<int, FakeMicroModem*> by_address;
  std::map<int, TcpPort*> tcp_by_address;
  try {
    for (size_t i = 0; i < modem_specs.size(); ++i) {
      FakeModemConfig config = parse_modem(modem_specs[i]);
      config.frame_error_probability = frame_errors;
      config.header_error_probability = header_errors;
      config.seed = seed + static_cast<uint32_t>(i);
      if (by_address.contains(config.address)) {
        throw CLI::ValidationError("--modem", "address " + std::to_string(config.address) + " is used twice");
      }
      auto& modem = modems.emplace_back(std::make_unique<FakeMicroModem>(water, config));
      by_address[config.address] = modem.get();
      std::string name = config.generation == Generation::kMM1 ? "mm1" : "mm2";
      if (transport == "pty") {
        auto& pty = ptys.emplace_back(std::make_unique<PtyPort>(context, *modem));
        std::cout << "modem " << config.address << " " << name << " pty " << pty->path() << std::endl;
      } else {
        uint16_t port = tcp_base_port == 0 ? 0 : static_cast<uint16_t>(tcp_base_port + i);
        auto& tcp = tcps.emplace_back(std::make_unique<TcpPort>(context, *modem, port));
        tcp_by_address[config.address] = tcp.get();
        std::cout << "modem " << config.address << " " << name << " tcp 127.0.0.1:" << tcp->port() << std::endl;
      }
    }
  } catch (const CLI::ValidationError& error) {
    return app.exit(error);
  } catch (const std::exception& error) {
    std::cerr << "fake_micromodem: " << error.what() << "\n";
    return 1;
  }
  for (auto& modem : modems) modem->power_on();
  LineConsole line_console(context, by_address, tcp_by_address);

  asio::posix::stream_descriptor console(context, ::dup(0));
  asio::streambuf input;
  std::function<void()> read_command = [&] {
    asio::async_read_until(console, input, '\n', [&](const std::error_code& error, size_t) {
      if (error) return;  // stdin closed: keep running without a console
      std::istream stream(&input);
      std::string line;
      std::getline(stream, line);
      if (!line.empty()) {
        std::optional<std::string> answer = line_console.run(line);
        std::cout << (answer ? *answer : run_fault_command(line, by_address)) << std::endl;
      }
      read_command();
    });
  };
  read_command();
  asio::signal_set signals(context, SIGINT, SIGTERM);
  signals.async_wait([&](const std::error_code&, int) { context.stop(); });
  context.run();
  return 0;
}
