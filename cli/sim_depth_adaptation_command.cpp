#include "sim_depth_adaptation_command.h"

#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "depth_adaptation_plot.h"
#include "eval/depth_adaptation.h"
#include "eval/depth_adaptation_sweep.h"
#include "global_options.h"
#include "gram/bellhop_import.h"
#include "gram/link_physics.h"

namespace acomms::cli {
namespace {

struct DepthAdaptationOptions {
  std::string env, png, model_env;
  eval::DepthAdaptationConfig config;
  double source_level_db = gram::kDefaultSourceLevelDb;
  std::optional<double> noise_level_db;
  gram::NoiseModelInput noise;  // centre: the environment's frequency
  std::optional<double> band_hz;  // unset: gram::default_band_hz
  std::optional<double> snr50_db;
  double slope_per_db = gram::kDefaultSlopePerDb;
  double excess_loss_db = 0;
  std::optional<double> own_ship_noise_db;
  std::vector<std::string> sweep;  // QUANTITY FROM:TO:STEP
};

// The evaluation names its config fields; a user of this command typed flags.
std::string in_flag_words(std::string message) {
  static const std::pair<const char*, const char*> kFlags[] = {
      {"fixed_depths_m", "--depths"},       {"buoy_depth_m", "--buoy-depth"},
      {"start_depth_m", "--start-depth"},   {"start_range_m", "--start-range"},
      {"max_range_m", "--max-range"},       {"speed_mps", "--speed"},
      {"send_interval_s", "--interval"},    {"vertical_speed_mps", "--vertical-speed"},
      {"horizon_s", "--tau-a"},             {"h_max_db", "--h-max"},
      {"bin_m", "--bin"},                   {"range_step_m", "--range-step"},
      {"depth_step_m", "--depth-step"},     {"laps", "--laps"},
      {"source_level_db", "--source-level"}, {"noise_level_db", "--noise-level"},
      {"sea_state", "--sea-state"},         {"band_hz", "--band"},
      {"shipping", "--shipping"},           {"limits.min_depth_m", "--min-depth"},
      {"limits.max_depth_m", "--max-depth"}, {"limits.min_altitude_m", "--min-altitude"},
      {"min_depth_m", "--min-depth"},       {"max_depth_m", "--max-depth"},
      {"min_altitude_m", "--min-altitude"}, {"excess_loss_db", "--excess-loss"},
      {"own_ship_noise_db", "--own-ship-noise"},
      {"noise_decrease_db_per_km", "--noise-decrease"},
      {"forecast_horizon_s", "--forecast-horizon"},
      {"caustic_uncertainty_m", "--caustic-uncertainty"}};
  for (const auto& [field, flag] : kFlags) {
    const std::string name = field;
    if (message.rfind(name + " ", 0) == 0) return flag + message.substr(name.size());
  }
  return message;
}

void run(DepthAdaptationOptions& o, const GlobalOptions& global) {
  gram::ImportedEnvironment imported;
  try {
    imported = gram::import_bellhop_env_file(o.env);
  } catch (const std::exception& e) {
    throw CLI::ValidationError("--env", e.what());
  }
  for (const auto& warning : imported.warnings) std::cerr << "acommsctl: " << o.env << ": " << warning << "\n";
  eval::DepthAdaptationConfig config = o.config;
  config.physics.source_level_db = o.source_level_db;
  if (o.noise_level_db) {
    config.physics.noise_level_db = *o.noise_level_db;
  } else {
    gram::NoiseModelInput noise = o.noise;
    noise.centre_hz = imported.environment.frequency_hz();
    noise.band_hz = o.band_hz ? *o.band_hz : gram::default_band_hz(noise.centre_hz);
    config.physics.noise_level_db = gram::modelled_noise_level_db(noise);
  }
  gram::ReceptionCurve curve = gram::default_reception_curve(config.rate);
  if (o.snr50_db) curve.snr50_db = *o.snr50_db;
  curve.slope_per_db = o.slope_per_db;
  if (auto problem = gram::validate_reception_curve(curve, "")) {
    const bool slope = problem->rfind("slope_per_db", 0) == 0;
    throw CLI::ValidationError(slope ? "--slope" : "--snr50", *problem);
  }
  config.physics.curves[config.rate] = curve;
  config.physics.site.excess_loss_db = o.excess_loss_db;
  config.physics.site.own_ship_noise_db = o.own_ship_noise_db;

  std::optional<gram::Environment> model;
  if (!o.model_env.empty()) {
    try {
      model = gram::import_bellhop_env_file(o.model_env).environment;
    } catch (const std::exception& e) {
      throw CLI::ValidationError("--model-env", e.what());
    }
  }
  if (!o.sweep.empty()) {
    eval::SweepQuantity quantity{};
    eval::SweepRange range;
    try {
      quantity = eval::sweep_quantity_from_string(o.sweep.at(0));
      range = eval::parse_sweep_range(o.sweep.at(1));
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("--sweep", e.what());
    }
    const std::vector<eval::SweepPoint> points =
        eval::run_depth_adaptation_sweep(imported.environment, config, model ? &*model : nullptr, quantity, range);
    if (!o.png.empty()) write_depth_adaptation_sweep_png(o.png, quantity, points, o.env, config.buoy_depth_m);
    std::cout << (global.json ? eval::format_sweep_json(quantity, points)
                              : eval::format_sweep_table(quantity, config, points))
              << std::flush;
    return;
  }
  const eval::DepthAdaptationResult result =
      eval::run_depth_adaptation(imported.environment, config, model ? &*model : nullptr);
  if (!o.png.empty()) write_depth_adaptation_png(o.png, result, o.env, config.buoy_depth_m);
  std::cout << (global.json ? eval::format_depth_adaptation_json(config, result)
                            : eval::format_depth_adaptation_table(config, result))
            << std::flush;
}

}  // namespace

void add_sim_depth_adaptation_command(CLI::App* sim, const GlobalOptions& global) {
  static DepthAdaptationOptions o;
  eval::DepthAdaptationConfig& c = o.config;
  CLI::App* command = sim->add_subcommand(
      "depth-adaptation",
      "The GLINT10 depth-adaptation experiment (Schneider 2013, section 4.3) on your environment: a "
      "buoy modem, a vehicle running out and back sending every 30 s, each packet received with the "
      "probability its modelled SNR = SL - TL - NL gives; the receipt probability per range bin at "
      "fixed depths and for a vehicle that moves toward the model's best depth, and whether adapting "
      "helped. Deterministic (seeded)");
  command->add_option("--env", o.env, "BELLHOP-format environment (its receiver grid is replaced)")
      ->required()
      ->type_name("FILE.env");
  command->add_option("--model-env", o.model_env,
                      "The environment the adaptive vehicle believes, when it differs from the water (default: "
                      "the water itself, a perfect model)")
      ->type_name("FILE.env");
  command->add_option("--png", o.png, "Also draw receipt probability against range, one colour per strategy")
      ->type_name("FILE");
  command->add_option("--buoy-depth", c.buoy_depth_m, "The buoy modem's depth, m")->capture_default_str();
  command->add_option("--start-range", c.start_range_m, "The vehicle starts (and ends) this far from the buoy, m")
      ->capture_default_str();
  command->add_option("--max-range", c.max_range_m, "The vehicle turns back at this range, m")->capture_default_str();
  command->add_option("--speed", c.speed_mps, "The vehicle's speed, m/s")->capture_default_str();
  command->add_option("--interval", c.send_interval_s, "Seconds between the vehicle's packets")->capture_default_str();
  command->add_option("--rate", c.rate, "Modem rate of the packets (0: FSK)")
      ->check(CLI::Range(0, 5))
      ->capture_default_str();
  command->add_option("--depths", c.fixed_depths_m, "The fixed depths to compare, m, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--start-depth", c.start_depth_m, "The adaptive vehicle's depth when it leaves, m")
      ->capture_default_str();
  command->add_option("--vertical-speed", c.vertical_speed_mps, "The adaptive vehicle's most vertical speed, m/s")
      ->capture_default_str();
  command->add_option("--tau-a", c.horizon_s, "Seconds between depth decisions (the model horizon tau_a)")
      ->capture_default_str();
  command->add_option("--h-max", c.h_max_db, "H_max of the objective (eq. 4.3), dB")->capture_default_str();
  command->add_option("--min-depth", c.limits.min_depth_m, "The adaptive vehicle's shallowest depth, m")
      ->capture_default_str();
  command->add_option("--max-depth", c.limits.max_depth_m, "Its deepest depth, m (0: only --min-altitude limits it)")
      ->capture_default_str();
  command->add_option("--min-altitude", c.limits.min_altitude_m, "Its clearance above the bottom, m")
      ->capture_default_str();
  command->add_option("--bin", c.bin_m, "Range bin of the report, m")->capture_default_str();
  command->add_option("--range-step", c.range_step_m, "The model's receiver range spacing, m")->capture_default_str();
  command->add_option("--depth-step", c.depth_step_m,
                      "The model's receiver depth spacing, m (0: 2 m, or a hundredth of the water column where "
                      "coarser)")
      ->capture_default_str();
  command->add_option("--laps", c.laps, "Runs out and back, each with fresh draws")->capture_default_str();
  command->add_option("--seed", c.seed, "Random seed (same seed, same output)")->capture_default_str();
  command->add_option("--threads", c.threads, "Model threads (0: all cores); the result is the same")
      ->capture_default_str();
  command->add_option("--source-level", o.source_level_db, "SL, dB re 1 uPa at 1 m")->capture_default_str();
  command->add_option("--noise-level", o.noise_level_db,
                      "NL in the band, dB re 1 uPa (default: the noise model with --sea-state and --band)");
  command->add_option("--sea-state", o.noise.sea_state, "Sea state for the noise model's wind (0..6)")
      ->capture_default_str();
  command->add_option("--band", o.band_hz,
                      "Receiver band around the environment's frequency, Hz (default: 4160 Hz at 25 kHz, the same "
                      "fraction of any other frequency)");
  command->add_option("--shipping", o.noise.shipping, "Shipping activity for the noise model, 0..1")
      ->capture_default_str();
  command->add_option("--snr50", o.snr50_db, "SNR (dB) at which half the packets decode (default: 10 rate 0, 14 PSK)");
  command->add_option("--slope", o.slope_per_db, "Logistic slope of the reception curve, 1/dB")->capture_default_str();
  command->add_option("--excess-loss", o.excess_loss_db,
                      "The site's excess loss, dB added to every TL (acommsctl link calibrate measures it)")
      ->capture_default_str();
  command->add_option("--own-ship-noise", o.own_ship_noise_db,
                      "The vehicle's own noise in the band, dB re 1 uPa, added to NL (powers sum)");
  command->add_option("--sweep", o.sweep,
                      "Run across a range instead: noise|excess-loss FROM:TO:STEP (dB); prints adaptive against the "
                      "best fixed depth, each with its standard error, per value")
      ->expected(2);
  command->add_option("--noise-decrease", c.noise_decrease_db_per_km,
                      "Deep water: NL falls by this many dB/km below the profile's critical depth (spec 6.6 after "
                      "Schneider 2013 4.4; 3 is typical); the adaptive vehicles then rank depths by signal excess");
  command->add_flag("--forecast", c.forecast,
                    "Also run the forecast strategy (deep water, Schneider 2013 4.4): plan over --forecast-horizon, "
                    "the depth path of most packets expected within the vertical speed (shadows score 0)");
  command->add_option("--forecast-horizon", c.forecast_horizon_s, "How far ahead the forecast looks, s")
      ->capture_default_str();
  command->add_option("--caustic-uncertainty", c.caustic_uncertainty_m,
                      "How well a caustic's depth is known, m: the forecast's objective is low-passed from the "
                      "surface with cutoff 1/this (0: none)")
      ->capture_default_str();
  command->footer(
      "Examples:\n"
      "  acommsctl sim depth-adaptation --env examples/glint10.env --png receipt.png\n"
      "  acommsctl sim depth-adaptation --env deep_munk.env --buoy-depth 200 --start-range 20000 --max-range 60000 \\\n"
      "      --start-depth 20 --depths 100,500,1000,2000,3000,4000 --tau-a 120 --forecast --forecast-horizon 3600 \\\n"
      "      --noise-decrease 3\n"
      "  acommsctl sim depth-adaptation --env examples/glint10.env --sweep noise 100:112:2 --laps 10\n"
      "  acommsctl --json sim depth-adaptation --env examples/glint10.env --depths 10,50,90 --laps 5");
  command->callback([&global] {
    try {
      run(o, global);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("sim depth-adaptation", in_flag_words(e.what()));
    }
  });
}

}  // namespace acomms::cli
