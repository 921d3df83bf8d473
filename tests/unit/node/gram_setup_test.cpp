// make_gram (daemon/node/gram_setup.h) builds its engine by name from the
// engines linked in (gram/engine_registry.h): an engine this test registers
// itself, under a name nothing else knows, is built and is named in the
// error for an unknown engine, with no list edited anywhere. Also: the
// default engine, and what an external engine is given.

#include "node/gram_setup.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "gram/engine_registry.h"
#include "store/store.h"

namespace acomms::node {
namespace {

namespace fs = std::filesystem;

// An engine of this test's own: flat 50 dB everywhere.
class FlatEngine final : public gram::ModelEngine {
 public:
  explicit FlatEngine(std::string name) : name_(std::move(name)) {}
  std::string name() const override { return name_; }
  gram::TransmissionLoss transmission_loss(const gram::Environment& env, const gram::CancelToken&) override {
    gram::TransmissionLoss tl;
    tl.range_m.assign(env.receiver_range_m().begin(), env.receiver_range_m().end());
    tl.depth_m.assign(env.receiver_depth_m().begin(), env.receiver_depth_m().end());
    tl.tl_db.assign(tl.range_m.size() * tl.depth_m.size(), 50.0);
    return tl;
  }

 private:
  std::string name_;
};

// Registered exactly as an engine registers itself.
const gram::EngineRegistrar flat_registrar("test_flat_engine", [](const gram::EngineSettings&) {
  return std::make_unique<FlatEngine>("test_flat_engine");
});

// An external engine of this test's own: keeps what it was given.
std::optional<gram::EngineSettings> external_given;
const gram::EngineRegistrar external_registrar(
    "test_external_engine",
    [](const gram::EngineSettings& settings) {
      external_given = settings;
      return std::make_unique<FlatEngine>("test_external_engine");
    },
    gram::EngineTraits{.external = true});

class GramSetupTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-gram-setup-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    store_ = std::make_unique<store::Store>(dir_.string());
    external_given.reset();
  }
  void TearDown() override {
    store_.reset();
    fs::remove_all(dir_);
  }

  GramParts make(const v1::GramConfig& config) { return make_gram(config, dir_.string(), store_->db()); }

  // The error make_gram throws, or "" when it builds.
  std::string error_of(const v1::GramConfig& config) {
    try {
      make(config);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
  std::unique_ptr<store::Store> store_;
};

TEST_F(GramSetupTest, AnEngineRegisteredByNameIsBuiltWithNoListEdited) {
  v1::GramConfig config;
  config.set_engine("test_flat_engine");
  GramParts parts = make(config);
  ASSERT_NE(parts.pool, nullptr);
  EXPECT_EQ(parts.pool->engine_name(), "test_flat_engine");
}

TEST_F(GramSetupTest, AnUnknownEngineIsRefusedNamingEveryRegisteredOne) {
  v1::GramConfig config;
  config.set_engine("no_such_engine");
  const std::string what = error_of(config);
  // Whatever is linked in, in the registry's order: no list to keep here either.
  std::string known;
  for (const std::string& name : gram::EngineRegistry::linked().names()) known += (known.empty() ? "" : ", ") + name;
  EXPECT_EQ(what, "gram.engine \"no_such_engine\" is not an engine (known: " + known + ")");
  for (const char* name : {"builtin", "bellhop", "test_flat_engine", "test_external_engine"}) {
    EXPECT_NE(what.find(name), std::string::npos) << name << " missing from: " << what;
  }
}

TEST_F(GramSetupTest, NoEngineNamedIsTheBuiltinOne) {
  GramParts parts = make(v1::GramConfig());
  EXPECT_EQ(parts.pool->engine_name(), "builtin");
}

TEST_F(GramSetupTest, AnExternalEngineGetsItsProgramARunDirectoryUnderTheDataDirAndItsTimeLimit) {
  v1::GramConfig config;
  config.set_engine("test_external_engine");
  config.set_bellhop_path("/opt/model/bin/run");
  config.set_engine_timeout_s(7.5);
  GramParts parts = make(config);
  EXPECT_EQ(parts.pool->engine_name(), "test_external_engine");
  ASSERT_TRUE(external_given.has_value());
  EXPECT_EQ(external_given->executable, "/opt/model/bin/run");
  EXPECT_EQ(external_given->work_root, (dir_ / "gram-runs").string());
  EXPECT_DOUBLE_EQ(external_given->timeout.count(), 7.5);

  config.clear_engine_timeout_s();
  make(config);
  EXPECT_DOUBLE_EQ(external_given->timeout.count(), 60.0);
}

TEST_F(GramSetupTest, AnExternalEngineWithoutItsProgramOrWithABadTimeLimitIsRefused) {
  v1::GramConfig config;
  config.set_engine("bellhop");
  EXPECT_EQ(error_of(config), "gram.engine is \"bellhop\" but gram.bellhop_path is empty");
  config.set_engine("test_external_engine");
  EXPECT_EQ(error_of(config), "gram.engine is \"test_external_engine\" but gram.bellhop_path is empty");
  EXPECT_FALSE(external_given.has_value());

  config.set_bellhop_path("/opt/model/bin/run");
  config.set_engine_timeout_s(0);
  EXPECT_EQ(error_of(config).rfind("gram.engine_timeout_s = 0", 0), 0u) << error_of(config);
  EXPECT_FALSE(external_given.has_value());
}

// An engine that runs in-process is given nothing and ignores the
// external engine's settings, as before.
TEST_F(GramSetupTest, AnInProcessEngineIgnoresTheExternalSettings) {
  v1::GramConfig config;
  config.set_engine("builtin");
  config.set_bellhop_path("/opt/model/bin/run");
  config.set_engine_timeout_s(0);  // not checked: no external run
  GramParts parts = make(config);
  EXPECT_EQ(parts.pool->engine_name(), "builtin");
}

}  // namespace
}  // namespace acomms::node
