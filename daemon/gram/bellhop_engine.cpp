// The external BELLHOP engine (see bellhop_engine.h), registered as
// "bellhop" (gram/engine_registry.h).
#include "gram/bellhop_engine.h"

#include <stdlib.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

#include "gram/bellhop_export.h"
#include "gram/engine_registry.h"
#include "gram/environment_validation.h"
#include "gram/external_process.h"
#include "gram/shd_file.h"

namespace acomms::gram {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRoot = "run";

// The run's private directory, removed however the run ends.
class RunDirectory {
 public:
  explicit RunDirectory(const std::string& root) {
    std::error_code ec;
    fs::create_directories(root, ec);
    std::string pattern = (fs::path(root) / "bellhop-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw EngineError("bellhop: cannot make a run directory under " + root + ": " + std::strerror(errno));
    path_ = pattern;
  }
  ~RunDirectory() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw EngineError("bellhop: cannot write " + path.string());
}

std::string describe(const ProcessResult& r, const std::string& executable, double timeout_s) {
  using End = ProcessResult::End;
  std::ostringstream why;
  why << "bellhop (" << executable << ") ";
  switch (r.end) {
    case End::kExited: why << "exited with status " << r.code; break;
    case End::kSignalled: why << "was killed by signal " << r.code; break;
    case End::kTimedOut: why << "ran past gram.engine_timeout_s = " << timeout_s << " s and was killed"; break;
    case End::kNotStarted: why << "could not be started"; break;
    case End::kCancelled: why << "was cancelled"; break;
  }
  if (!r.output.empty()) why << ": " << r.output;
  return why.str();
}

class BellhopEngine final : public ModelEngine {
 public:
  explicit BellhopEngine(BellhopOptions options) : options_(std::move(options)) {}
  std::string name() const override { return "bellhop"; }

  TransmissionLoss transmission_loss(const Environment& env, const CancelToken& cancel) override {
    if (auto error = validate_environment(env)) throw std::invalid_argument(*error);
    RunDirectory dir(options_.work_root);
    const BellhopInput input = export_bellhop(env);
    write_file(dir.path() / (std::string(kRoot) + ".env"), input.env);
    if (input.bty) write_file(dir.path() / (std::string(kRoot) + ".bty"), *input.bty);
    const ProcessResult result = run_process(options_.executable, {kRoot}, dir.path().string(), options_.timeout, cancel);
    if (result.end == ProcessResult::End::kCancelled) throw ModelCancelled();
    if (result.end != ProcessResult::End::kExited || result.code != 0)
      throw EngineError(describe(result, options_.executable, options_.timeout.count()));
    const fs::path shd = dir.path() / (std::string(kRoot) + ".shd");
    std::ifstream in(shd, std::ios::binary);
    if (!in)
      throw EngineError("bellhop (" + options_.executable + ") exited with status 0 but wrote no " + kRoot +
                        ".shd" + (result.output.empty() ? "" : ": " + result.output));
    std::ostringstream bytes;
    bytes << in.rdbuf();
    try {
      return tl_from_shd(read_shd(bytes.str(), "bellhop's " + std::string(kRoot) + ".shd"), env);
    } catch (const ShdError& e) {
      throw EngineError(e.what());
    }
  }

 private:
  BellhopOptions options_;
};

// An external engine: the daemon gives it the program (gram.bellhop_path),
// a run directory under its data dir and gram.engine_timeout_s.
const EngineRegistrar registrar(
    "bellhop",
    [](const EngineSettings& settings) {
      return make_bellhop_engine({settings.executable, settings.work_root, settings.timeout});
    },
    EngineTraits{.external = true});

}  // namespace

std::unique_ptr<ModelEngine> make_bellhop_engine(const BellhopOptions& options) {
  return std::make_unique<BellhopEngine>(options);
}

TransmissionLoss tl_from_shd(const ShdField& field, const Environment& env) {
  const std::size_t nrz = field.receiver_depth_m.size(), nrr = field.receiver_range_m.size();
  const std::size_t want_z = env.receiver_depth_m_size(), want_r = env.receiver_range_m_size();
  if (field.source_depth_m.empty() || nrz != want_z || nrr != want_r)
    throw EngineError("bellhop's .shd has " + std::to_string(nrz) + " receiver depths × " + std::to_string(nrr) +
                      " ranges; the environment has " + std::to_string(want_z) + " × " + std::to_string(want_r));
  TransmissionLoss tl;
  tl.range_m.assign(env.receiver_range_m().begin(), env.receiver_range_m().end());
  tl.depth_m.assign(env.receiver_depth_m().begin(), env.receiver_depth_m().end());
  tl.irregular = env.irregular_receivers();
  tl.beam_count = env.beam_count();
  auto db = [](std::complex<float> p) {
    const double magnitude = std::abs(std::complex<double>(p));
    return magnitude > 0 ? -20.0 * std::log10(magnitude) : std::numeric_limits<double>::infinity();
  };
  // First frequency, first bearing, first source depth: records 0..NRz-1.
  if (tl.irregular) {
    for (std::size_t i = 0; i < want_r; ++i) tl.tl_db.push_back(db(field.pressure[i * nrr + i]));
  } else {
    for (std::size_t iz = 0; iz < nrz; ++iz)
      for (std::size_t ir = 0; ir < nrr; ++ir) tl.tl_db.push_back(db(field.pressure[iz * nrr + ir]));
  }
  return tl;
}

}  // namespace acomms::gram
