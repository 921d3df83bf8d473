#include "sim_telemetry_command.h"

#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "comma_list.h"
#include "eval/telemetry_evaluation.h"
#include "eval/realistic_track.h"
#include "eval/track_generator.h"
#include "global_options.h"
#include "telemetry/sampler.h"

namespace acomms::cli {
namespace {

struct TelemetryOptions {
  std::string track;
  std::string generate;
  bool realistic = false;
  double duration_s = 4 * 3600;
  std::string observers = "fixed_speed,kalman";
  std::string models = "uniform,gaussian,adaptive,learned";
  telemetry::TelemetryConfig config;
  std::vector<int32_t> bounds = {-50, 51};
  eval::TelemetryLossConfig loss;
};

void run(const TelemetryOptions& options, const GlobalOptions& global) {
  if (!options.generate.empty()) {
    const eval::TrackKind kind = eval::track_kind_of(options.generate);
    const std::vector<telemetry::Fix> track =
        options.realistic ? eval::generate_realistic_track(kind, options.loss.seed, options.duration_s)
                          : eval::generate_track(kind, options.loss.seed, options.duration_s);
    std::cout << eval::format_track_csv(track) << std::flush;
    return;
  }
  if (options.track.empty()) throw CLI::ValidationError("--track", "needed (or --generate auv|glider)");
  if (options.bounds.size() != 2 || options.bounds[0] >= 0 || options.bounds[1] <= 0)
    throw CLI::ValidationError("--bounds", "two values MIN,MAX with MIN < 0 < MAX (innovations in [MIN, MAX))");
  std::vector<telemetry::ObserverKind> observers;
  for (const std::string& name : split_commas(options.observers)) {
    auto kind = telemetry::observer_kind_of(name);
    if (!kind) throw CLI::ValidationError("--observer", "'" + name + "': use fixed_speed or kalman");
    observers.push_back(*kind);
  }
  std::vector<telemetry::ModelKind> models;
  for (const std::string& name : split_commas(options.models)) {
    auto kind = telemetry::model_kind_of(name);
    if (!kind) throw CLI::ValidationError("--model", "'" + name + "': use uniform, gaussian, adaptive or learned");
    models.push_back(*kind);
  }
  telemetry::TelemetryConfig config = options.config;
  config.innovation_min = options.bounds[0];
  config.innovation_max = options.bounds[1];
  try {
    telemetry::validate(config);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("sim telemetry", e.what());
  }
  std::vector<telemetry::Fix> fixes;
  try {
    fixes = eval::read_track_csv(options.track);
  } catch (const std::runtime_error& e) {
    throw CLI::ValidationError("--track", e.what());
  }
  const std::vector<telemetry::Sample> samples = telemetry::sample_track(fixes, config.tau_s);
  std::vector<eval::TelemetryRun> runs;
  for (telemetry::ObserverKind observer : observers) {
    for (telemetry::ModelKind model : models) {
      config.observer = observer;
      config.model = model;
      runs.push_back(eval::evaluate_telemetry(samples, config, options.loss));
    }
  }
  if (global.json) {
    std::cout << eval::format_telemetry_json(options.track, fixes.size(), runs) << std::flush;
  } else {
    std::cout << "track " << options.track << ": " << fixes.size() << " fixes, " << samples.size()
              << " samples every " << config.tau_s << " s\n"
              << eval::format_telemetry_table(runs) << std::flush;
  }
}

}  // namespace

void add_sim_telemetry_command(CLI::App* sim, const GlobalOptions& global) {
  static TelemetryOptions options;
  CLI::App* command = sim->add_subcommand(
      "telemetry",
      "Position telemetry by matched state observers (Schneider 2013, ch. 3) on a track: for each "
      "observer and model, delta and full transmissions, mean and standard deviation of a delta's "
      "codeword bits, message bits per position and compression against 96 bits. Every message is "
      "decoded again and compared (a mismatch is an error). --loss adds Bernoulli packet loss with "
      "resends");
  command->add_option("--track", options.track, "CSV with header t,x,y,z (s, m, z negative down)")
      ->check(CLI::ExistingFile);
  command->add_option("--generate", options.generate,
                      "Print a generated track instead (auv: 1.5 m/s lawnmower with yo-yo; glider: "
                      "0.3 m/s sawtooth with currents), seeded by --seed")
      ->check(CLI::IsMember({"auv", "glider"}));
  command->add_flag("--realistic", options.realistic,
                    "--generate: a realistic track instead (auv: torpedo AUV on irregular legs, currents, depth "
                    "changes and yo-yo with overshoot, DVL-aided INS drift and GPS jumps at surfacings, 1 Hz; "
                    "glider: dead-reckoned sawtooth, currents changing over hours, 4 s); see "
                    "daemon/eval/realistic_track.h");
  command->add_option("--duration", options.duration_s, "--generate: seconds of track")
      ->check(CLI::Range(60.0, 30 * 86400.0))
      ->capture_default_str();
  command->add_option("--observer", options.observers, "Observers, comma-separated: fixed_speed, kalman")
      ->capture_default_str();
  command->add_option("--model", options.models, "Models, comma-separated: uniform, gaussian, adaptive, learned")
      ->capture_default_str();
  command->add_option("--tau", options.config.tau_s, "Sampling period, whole seconds")
      ->check(CLI::Range(1u, 3600u))
      ->capture_default_str();
  command->add_option("--precision", options.config.precision_m, "Position precision, m")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  command->add_option("--speed", options.config.speed_mps, "Fixed-speed observer: vehicle speed, m/s")
      ->check(CLI::Range(0.001, 100.0))
      ->capture_default_str();
  command->add_option("--sigma-j2", options.config.sigma_j2, "Kalman: jerk variance sigma_j^2")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--r", options.config.r_m2, "Kalman: measurement noise R, m^2")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--bounds", options.bounds, "Innovation bounds MIN,MAX in precision steps: [MIN, MAX)")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  command->add_option("--full-every", options.config.full_every, "A full transmission after this many deltas")
      ->check(CLI::Range(1u, 10000u))
      ->capture_default_str();
  command->add_option("--loss", options.loss.loss, "Packet loss probability P (resends until delivered)")
      ->check(CLI::Range(0.0, 0.95))
      ->capture_default_str();
  command->add_option("--packet-bits", options.loss.packet_bits, "--loss: bits per packet (one per tau)")
      ->check(CLI::Range(64u, 1u << 20))
      ->capture_default_str();
  command->add_option("--seed", options.loss.seed, "Random seed for --loss and --generate")->capture_default_str();
  command->footer(
      "Examples:\n"
      "  acommsctl sim telemetry --track examples/tracks/auv_lawnmower.csv --observer kalman --model adaptive\n"
      "  acommsctl sim telemetry --generate glider --duration 86400 --seed 3 > glider.csv\n"
      "  acommsctl sim telemetry --generate auv --realistic --duration 10800 --seed 1 > torpedo.csv\n"
      "  acommsctl sim telemetry --track torpedo.csv --speed 1.5");
  command->callback([&global] {
    try {
      run(options, global);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("sim telemetry", e.what());
    }
  });
}

}  // namespace acomms::cli
