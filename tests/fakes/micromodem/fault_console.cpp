#include "fault_console.h"

#include <sstream>

namespace acomms::fake_micromodem {

std::string run_fault_command(const std::string& line, const std::map<int, FakeMicroModem*>& modems) {
  std::istringstream in(line);
  int address = -1;
  std::string command;
  if (!(in >> address >> command)) return "usage: <address> <command> [arguments]";
  auto found = modems.find(address);
  if (found == modems.end()) return "no fake modem with address " + std::to_string(address);
  FakeMicroModem& modem = *found->second;
  long count = 0;
  if (command == "checksum" && in >> count && count > 0) {
    modem.faults().corrupt_checksums(static_cast<int>(count));
  } else if (command == "truncate" && in >> count && count > 0) {
    modem.faults().truncate_lines(static_cast<int>(count));
  } else if (command == "noise" && in >> count && count > 0 && count <= 1 << 20) {
    modem.write_raw(modem.faults().noise_burst(static_cast<size_t>(count)));
  } else if (command == "overlong" && in >> count && count > 0 && count <= 1 << 20) {
    modem.write_raw(FaultInjector::overlong_line(static_cast<size_t>(count)));
  } else if (command == "unknown") {
    modem.write_raw(FaultInjector::unknown_sentence());
  } else if (command == "error") {
    std::string module, number, message;
    if (!(in >> module >> number)) return "usage: <address> error <module> <number> <message>";
    std::getline(in >> std::ws, message);
    modem.report_error(module, number, message);
  } else if (command == "reset") {
    modem.reboot();
  } else if (command == "reset-mid-tx") {
    modem.reboot_mid_next_transmission();
  } else if (command == "silent") {
    std::string state;
    in >> state;
    if (state != "on" && state != "off") return "usage: <address> silent on|off";
    modem.faults().set_silent(state == "on");
  } else if (command == "move") {
    Position p;
    if (!(in >> p.x >> p.y >> p.z)) return "usage: <address> move <x> <y> <z>";
    modem.move_to(p);
  } else {
    return "unknown or incomplete command '" + line + "'";
  }
  return "ok";
}

}  // namespace acomms::fake_micromodem
