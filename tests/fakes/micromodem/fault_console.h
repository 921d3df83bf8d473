#pragma once
// The fake_micromodem executable's fault console: one command per line on
// stdin, so a person or an integration test can hurt a running fake modem.
//   <address> checksum <n>        next n lines with a wrong checksum
//   <address> truncate <n>        next n lines cut short
//   <address> noise <bytes>       a burst of random bytes
//   <address> overlong <chars>    one line longer than any reader allows
//   <address> unknown             a well-formed sentence nobody knows
//   <address> error <module> <number> <message...>   a $CAERR
//   <address> reset               reboot ($CAREV,...,INIT)
//   <address> reset-mid-tx        reboot halfway through its next data packet
//   <address> silent on|off       stop / resume all output
//   <address> move <x> <y> <z>    new position, metres

#include <map>
#include <string>

#include "fake_micromodem.h"

namespace acomms::fake_micromodem {

// Runs one command line. Returns "ok" or what was wrong with the line.
std::string run_fault_command(const std::string& line, const std::map<int, FakeMicroModem*>& modems);

}  // namespace acomms::fake_micromodem
