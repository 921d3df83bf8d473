// A stand-in for the BELLHOP executable (`fake_bellhop [--layout 2022] ROOT`),
// for tests of the external engine: reads ROOT.env in the working
// directory with our own importer (so the .env the daemon wrote must be
// one BELLHOP-format readers accept) and writes ROOT.shd with a KNOWN
// field, TL(z, r) = 20 log10(r) + z / 10 dB, in the 2023 layout or, with
// --layout 2022, the older one. Exit 4 with a message if the .env is refused.
#include <cmath>
#include <complex>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include "gram/bellhop_import.h"
#include "gram/shd_file.h"

int main(int argc, char** argv) {
  using namespace acomms::gram;
  ShdLayout layout = ShdLayout::k2023;
  int arg = 1;
  if (argc > 2 && std::strcmp(argv[1], "--layout") == 0) {
    layout = std::strcmp(argv[2], "2022") == 0 ? ShdLayout::k2022 : ShdLayout::k2023;
    arg = 3;
  }
  if (arg >= argc) {
    std::cerr << "usage: fake_bellhop [--layout 2022|2023] ROOT\n";
    return 2;
  }
  const std::string root = argv[arg];
  Environment env;
  try {
    env = import_bellhop_env_file(root + ".env").environment;
  } catch (const std::exception& e) {
    std::cerr << "fake_bellhop: " << e.what() << "\n";
    return 4;
  }
  ShdField field;
  field.title = env.title();
  field.plot_type = env.irregular_receivers() ? "irregular" : "rectilin";
  field.freq = {env.frequency_hz()};
  field.theta = {0.0};
  field.sx = {0.0};
  field.sy = {0.0};
  field.source_depth_m = {static_cast<float>(env.source_depth_m())};
  for (double z : env.receiver_depth_m()) field.receiver_depth_m.push_back(static_cast<float>(z));
  field.receiver_range_m.assign(env.receiver_range_m().begin(), env.receiver_range_m().end());
  for (double z : env.receiver_depth_m())
    for (double r : env.receiver_range_m()) {
      const double tl = 20.0 * std::log10(r) + z / 10.0;
      field.pressure.emplace_back(static_cast<float>(std::pow(10.0, -tl / 20.0)), 0.0f);
    }
  std::ofstream(root + ".shd", std::ios::binary) << write_shd(field, layout);
  std::cout << "fake_bellhop: wrote " << root << ".shd\n";
  return 0;
}
