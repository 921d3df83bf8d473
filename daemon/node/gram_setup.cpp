#include "node/gram_setup.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "gram/engine_registry.h"
#include "util/bound_text.h"
#include "util/seconds.h"

namespace acomms::node {
namespace {

constexpr unsigned kDefaultWorkers = 1;
constexpr unsigned kMaxWorkers = 64;
constexpr unsigned kDefaultQueueLimit = 16;
constexpr unsigned kMaxQueueLimit = 10000;
constexpr double kDefaultCacheMb = 64;
constexpr double kDefaultEngineTimeoutS = 60;
// gram.engine when unset (api/proto/acomms/v1/config.proto).
constexpr std::string_view kDefaultEngine = "builtin";

double positive(const char* name, bool has, double value, double fallback, bool zero_ok = false) {
  if (!has) return fallback;
  if (!std::isfinite(value) || value < 0 || (!zero_ok && value == 0))
    throw std::runtime_error(util::must_be(std::string("gram.") + name, std::to_string(value),
                                           zero_ok ? "at least 0" : "greater than 0"));
  return value;
}

// The engine gram.engine names, from the engines linked in: an engine
// added registers itself (gram/engine_registry.h), nothing here lists them.
std::unique_ptr<gram::ModelEngine> make_engine(const v1::GramConfig& c, const std::string& data_dir) {
  const gram::EngineRegistry& engines = gram::EngineRegistry::linked();
  const std::string name = c.engine().empty() ? std::string(kDefaultEngine) : c.engine();
  if (!engines.contains(name)) {
    std::string known;
    for (const std::string& n : engines.names()) known += (known.empty() ? "" : ", ") + n;
    throw std::runtime_error("gram.engine \"" + name + "\" is not an engine (known: " + known + ")");
  }
  gram::EngineSettings settings;
  if (!engines.traits(name).external) {
    if (!c.bellhop_path().empty())
      spdlog::warn("gram.bellhop_path is set but gram.engine is \"{}\": BELLHOP is not used", name);
    return engines.create(name, settings);
  }
  if (c.bellhop_path().empty())
    throw std::runtime_error("gram.engine is \"" + name + "\" but gram.bellhop_path is empty");
  settings.executable = c.bellhop_path();
  // Under the store: the service unit's file system is read-only elsewhere.
  settings.work_root = (std::filesystem::path(data_dir) / "gram-runs").string();
  settings.timeout = std::chrono::duration<double>(
      positive("engine_timeout_s", c.has_engine_timeout_s(), c.engine_timeout_s(), kDefaultEngineTimeoutS));
  return engines.create(name, settings);
}

}  // namespace

GramParts make_gram(const v1::GramConfig& c, const std::string& data_dir, store::Database& db) {
  gram::ModelPoolOptions pool;
  pool.workers = c.has_workers() ? c.workers() : kDefaultWorkers;
  if (pool.workers < 1 || pool.workers > kMaxWorkers)
    throw std::runtime_error(
        util::must_be("gram.workers", std::to_string(pool.workers), util::within("1", std::to_string(kMaxWorkers))));
  pool.queue_limit = c.has_queue_limit() ? c.queue_limit() : kDefaultQueueLimit;
  if (pool.queue_limit < 1 || pool.queue_limit > kMaxQueueLimit)
    throw std::runtime_error(util::must_be("gram.queue_limit", std::to_string(pool.queue_limit),
                                           util::within("1", std::to_string(kMaxQueueLimit))));
  pool.cache_bytes = static_cast<std::size_t>(
      positive("cache_mb", c.has_cache_mb(), c.cache_mb(), kDefaultCacheMb, true) * (1 << 20));

  gram::VehicleEnvironmentOptions env;
  env.ctd_bin_m = positive("ctd_bin_m", c.has_ctd_bin_m(), c.ctd_bin_m(), env.ctd_bin_m);
  env.ctd_thin_mps = positive("ctd_thin_mps", c.has_ctd_thin_mps(), c.ctd_thin_mps(), env.ctd_thin_mps, true);
  env.instance_window_s =
      positive("instance_window_s", c.has_instance_window_s(), c.instance_window_s(), env.instance_window_s, true);

  GramParts parts;
  parts.environment = std::make_unique<gram::VehicleEnvironment>(c.base(), env);
  store::Statement read = db.prepare("SELECT state FROM gram_environment WHERE id = 1");
  if (read.step()) {
    gram::KnownEnvironment stored;
    if (stored.ParseFromString(read.column_blob(0))) {
      parts.environment->restore(std::move(stored));
      spdlog::info("gram: environment restored from the store ({} profile instance(s))",
                   parts.environment->snapshot().instances_size());
    } else {
      spdlog::error("gram: the stored environment cannot be parsed; starting from the config's base");
    }
  }
  auto engine = make_engine(c, data_dir);
  spdlog::info("gram: {} worker(s), queue limit {}, cache {:.0f} MB, engine {}", pool.workers, pool.queue_limit,
               pool.cache_bytes / double(1 << 20), engine->name());
  parts.pool = std::make_unique<gram::ModelPool>(pool, std::move(engine));
  return parts;
}

service::SaveEnvironment save_environment_to(store::GroupCommitWriter& writer) {
  return [&writer](const gram::KnownEnvironment& state, std::function<void(std::exception_ptr)> done) {
    std::string bytes = state.SerializeAsString();
    const double now = util::unix_seconds_now();
    try {
      writer.post(
          [bytes = std::move(bytes), now](store::Database& db) {
            db.prepare("INSERT OR REPLACE INTO gram_environment (id, state, updated_at) VALUES (1, ?, ?)")
                .bind_blob(1, bytes)
                .bind_double(2, now)
                .step();
          },
          done);  // a copy: still ours if post throws
    } catch (...) {
      done(std::current_exception());  // the writer is stopped
    }
  };
}

}  // namespace acomms::node
