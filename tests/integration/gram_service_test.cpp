// acomms.v1.Gram against the real acommsd: every call, and every error
// status a client can get (supersede, deadline, cancel, full queue, cache
// hit, a bad environment naming the field); DepthObjective checked against
// the conformance files and against eq. 4.2–4.4 on the daemon's own TL
// answers; an environment update surviving a SIGKILL and restart.
//
// "Waiting" and "running" are states the test observes through PoolStatus
// (never a sleep): a slow run is started, the test waits until the pool
// says it runs, then queues behind it.
#include <google/protobuf/text_format.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>

#include "acomms/v1/gram.grpc.pb.h"
#include "child_process.h"
#include "daemon_harness.h"
#include "gram/bellhop_import.h"
#include "gram/depth_lowpass.h"
#include "gram/range_averaged_tl.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kAcommsd = ACOMMSD_BINARY;
const std::string kShared = ACOMMS_SHARED_DIR;

std::vector<std::map<std::string, std::string>> read_csv(const std::string& name) {
  std::ifstream in(kShared + "/conformance/gram/" + name);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) header.push_back(cell);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::stringstream ls(line);
    std::map<std::string, std::string> row;
    std::size_t i = 0;
    for (std::string cell; i < header.size() && std::getline(ls, cell, ','); ++i) row[header[i]] = cell;
    rows.push_back(row);
  }
  return rows;
}

gram::Environment base_environment() {
  return gram::import_bellhop_env_file(kShared + "/conformance/gram/envs/pekeris_lossy_500hz.env").environment;
}

std::string cast_csv(double surface_degc) {
  std::ostringstream csv;
  csv << "lat_deg,depth_m,t90_degc,s_psu\n";
  for (int z = 0; z <= 100; z += 2) csv << "45," << z << "," << surface_degc - z * 0.08 << ",35\n";
  return csv.str();
}

class GramServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    socket_ = (dir_ / "api.sock").string();
    config_ = (dir_ / "acommsd.conf").string();
    write_config("");
  }
  void TearDown() override {
    daemon_.reset();
  }

  void write_config(const std::string& gram_extra) {
    std::string base;
    google::protobuf::TextFormat::PrintToString(base_environment(), &base);
    DaemonConfig{.data_dir = dir_ / "data",
                 .unix_socket = socket_,
                 .rest = "gram { workers: 1 queue_limit: 1 cache_mb: 16 " + gram_extra + "\n base {\n" + base + "} }\n"}
        .write(config_);
  }
  void start() {
    daemon_ = std::make_unique<ChildProcess>(kAcommsd, std::vector<std::string>{"--config", config_},
                                             (dir_ / ("acommsd" + std::to_string(++starts_))).string());
    ASSERT_TRUE(wait_serving(*daemon_, socket_)) << daemon_->stderr_text();
    stub_ = v1::Gram::NewStub(grpc::CreateChannel("unix:" + socket_, grpc::InsecureChannelCredentials()));
  }
  static std::unique_ptr<grpc::ClientContext> context(std::chrono::milliseconds deadline = 60s) {
    auto c = std::make_unique<grpc::ClientContext>();
    c->set_deadline(std::chrono::system_clock::now() + deadline);
    return c;
  }
  v1::PoolStatusReply pool() {
    v1::PoolStatusReply reply;
    EXPECT_TRUE(stub_->PoolStatus(context().get(), v1::PoolStatusRequest(), &reply).ok());
    return reply;
  }
  // A run far longer than any test: the most beams on a dense grid.
  static v1::TransmissionLossRequest slow_request() {
    v1::TransmissionLossRequest request;
    auto* env = request.mutable_header()->mutable_environment();
    env->set_beam_count(100000);
    for (int i = 1; i <= 2000; ++i) env->add_receiver_range_m(5.0 * i);
    return request;
  }

  struct Call {
    grpc::ClientContext context;
    v1::TransmissionLossReply reply;
    std::promise<grpc::Status> done;
    std::future<grpc::Status> status = done.get_future();
  };
  std::unique_ptr<Call> start_tl(const v1::TransmissionLossRequest& request, std::chrono::milliseconds deadline = 120s) {
    auto call = std::make_unique<Call>();
    call->context.set_deadline(std::chrono::system_clock::now() + deadline);
    stub_->async()->TransmissionLoss(&call->context, &request, &call->reply,
                                     [c = call.get()](grpc::Status s) { c->done.set_value(s); });
    return call;
  }
  bool pool_reaches(const std::function<bool(const v1::PoolStatusReply&)>& condition) {
    return wait_until([&] { return condition(pool()); }, 20s);
  }

  int starts_ = 0;
  // Short base path: unix socket paths are limited to 107 bytes.
  TempDir dir_{"acomms-gram-it", "/tmp"};
  std::string socket_, config_;
  std::unique_ptr<ChildProcess> daemon_;
  std::unique_ptr<v1::Gram::Stub> stub_;
};

TEST_F(GramServiceTest, TransmissionLossRunsAndAnIdenticalRequestIsACacheHit) {
  start();
  v1::TransmissionLossRequest request;
  request.mutable_header()->mutable_environment()->set_source_depth_m(30);
  v1::TransmissionLossReply first, second;
  ASSERT_TRUE(stub_->TransmissionLoss(context().get(), request, &first).ok());
  EXPECT_FALSE(first.from_cache());
  EXPECT_EQ(first.engine(), "builtin");
  EXPECT_EQ(first.tl_db_size(), 25 * 393);
  ASSERT_TRUE(stub_->TransmissionLoss(context().get(), request, &second).ok());
  EXPECT_TRUE(second.from_cache());
  EXPECT_EQ(second.tl_db_size(), first.tl_db_size());
  for (int i = 0; i < first.tl_db_size(); ++i)
    if (!std::isnan(first.tl_db(i))) {
      ASSERT_EQ(second.tl_db(i), first.tl_db(i)) << i;
    }
  EXPECT_EQ(pool().cache_hits(), 1u);
}

TEST_F(GramServiceTest, ArrivalsAreAnsweredPerReceiver) {
  start();
  v1::ArrivalsRequest request;
  auto* env = request.mutable_header()->mutable_environment();
  env->set_irregular_receivers(true);
  env->add_receiver_range_m(2000);
  env->add_receiver_depth_m(50);
  request.set_max_arrivals(20);
  v1::ArrivalsReply reply;
  grpc::Status status = stub_->Arrivals(context().get(), request, &reply);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(reply.receivers_size(), 1);
  EXPECT_EQ(reply.receivers(0).range_m(), 2000);
  EXPECT_GT(reply.receivers(0).arrivals_size(), 2);
  EXPECT_LE(reply.receivers(0).arrivals_size(), 20);
  EXPECT_GT(reply.receivers(0).rms_delay_spread_s(), 0);
}

TEST_F(GramServiceTest, ABadEnvironmentIsRefusedNamingTheField) {
  start();
  v1::TransmissionLossRequest request;
  auto* env = request.mutable_header()->mutable_environment();
  auto* p0 = env->add_sound_speed();
  p0->set_depth_m(0);
  p0->set_speed_mps(1500);
  auto* p1 = env->add_sound_speed();
  p1->set_depth_m(-10);
  p1->set_speed_mps(1500);
  v1::TransmissionLossReply reply;
  grpc::Status status = stub_->TransmissionLoss(context().get(), request, &reply);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("sound_speed[1].depth_m = -10"), std::string::npos) << status.error_message();

  v1::TransmissionLossRequest masked;
  masked.mutable_header()->mutable_override_mask()->add_paths("bottom.knd");
  status = stub_->TransmissionLoss(context().get(), masked, &reply);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("\"bottom.knd\""), std::string::npos) << status.error_message();
}

// Supersede, full queue and cancel, one after another behind one slow run.
TEST_F(GramServiceTest, SupersedeFullQueueAndCancelBehindARunningModel) {
  start();
  auto slow = start_tl(slow_request());
  ASSERT_TRUE(pool_reaches([](const auto& p) { return p.running() == 1; }));

  v1::TransmissionLossRequest mine;
  mine.mutable_header()->set_consumer("depth-behaviour");
  mine.mutable_header()->mutable_environment()->set_source_depth_m(20);
  auto older = start_tl(mine);
  ASSERT_TRUE(pool_reaches([](const auto& p) { return p.waiting() == 1; }));
  mine.mutable_header()->mutable_environment()->set_source_depth_m(21);
  auto newer = start_tl(mine);
  grpc::Status superseded = older->status.get();
  EXPECT_EQ(superseded.error_code(), grpc::StatusCode::ABORTED);
  EXPECT_NE(superseded.error_message().find("\"depth-behaviour\""), std::string::npos) << superseded.error_message();

  // queue_limit 1: the newer request waits, one more does not fit.
  v1::TransmissionLossRequest another;
  another.mutable_header()->mutable_environment()->set_source_depth_m(22);
  v1::TransmissionLossReply reply;
  grpc::Status full = stub_->TransmissionLoss(context().get(), another, &reply);
  EXPECT_EQ(full.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(full.error_message().find("queue_limit = 1"), std::string::npos) << full.error_message();

  // The client cancels the slow run: it stops, and the one worker takes the
  // waiting request. Had the slow run gone on to its end (minutes), the
  // newer request would have waited for it and its answer would be in the
  // cache beside the newer one's. (How soon a cancel frees the worker:
  // tests/bench/gram_pool_bench.)
  slow->context.TryCancel();
  EXPECT_EQ(slow->status.get().error_code(), grpc::StatusCode::CANCELLED);
  grpc::Status answered = newer->status.get();
  ASSERT_TRUE(answered.ok()) << answered.error_message();
  EXPECT_FALSE(newer->reply.from_cache());
  EXPECT_EQ(pool().cache_entries(), 1u) << "the cancelled run finished and kept its answer";
}

// The run ends (the worker is free) with no answer kept: it was stopped,
// not run to its end (minutes). How soon: tests/bench/gram_pool_bench.
TEST_F(GramServiceTest, ADeadlineStopsARunningModelAndFreesTheWorker) {
  start();
  const auto before = pool().completed();
  auto slow = start_tl(slow_request(), 500ms);
  EXPECT_EQ(slow->status.get().error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  ASSERT_TRUE(pool_reaches([&](const auto& p) { return p.running() == 0 && p.completed() > before; }));
  EXPECT_EQ(pool().cache_entries(), 0u) << "the expired run finished and kept its answer";
}

TEST_F(GramServiceTest, AnEnvironmentUpdateSurvivesAKillAndRestart) {
  start();
  v1::UpdateEnvironmentRequest update;
  update.mutable_base()->set_source_depth_m(42);
  auto* cast = update.add_casts();
  cast->set_time_s(1.7e9);
  cast->set_csv(cast_csv(18));
  cast->set_name("cast1.csv");
  gram::KnownEnvironment updated;
  grpc::Status status = stub_->UpdateEnvironment(context().get(), update, &updated);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(updated.instances_size(), 1);
  EXPECT_EQ(updated.instances(0).samples(), 51u);
  EXPECT_EQ(updated.base().source_depth_m(), 42);

  v1::UpdateEnvironmentRequest bad;
  bad.add_casts()->set_csv("lat_deg,depth_m,t90_degc,s_psu\n45,0,10,35\n45,oops,10,35\n");
  bad.mutable_casts(0)->set_name("bad.csv");
  gram::KnownEnvironment unchanged;
  status = stub_->UpdateEnvironment(context().get(), bad, &unchanged);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("bad.csv"), std::string::npos) << status.error_message();

  daemon_->signal(SIGKILL);
  daemon_->wait(10s);
  start();
  gram::KnownEnvironment held;
  ASSERT_TRUE(stub_->GetEnvironment(context().get(), v1::GetEnvironmentRequest(), &held).ok());
  EXPECT_EQ(held.SerializeAsString(), updated.SerializeAsString()) << held.DebugString();
}

// DepthObjective with two profile instances: H̄ is eq. 4.4 over the
// per-instance eq. 4.2 averages of the daemon's own TL answers; O is eq.
// 4.3; the low-pass is §6.4; the window is eq. 4.1 as in the conformance
// file; NL and SE are the conformance file's.
TEST_F(GramServiceTest, DepthObjectiveAveragesTheInstancesAsTheConformanceFilesSay) {
  start();
  v1::UpdateEnvironmentRequest update;
  for (double warm : {16.0, 22.0}) {
    auto* cast = update.add_casts();
    cast->set_time_s(1.7e9 + warm);
    cast->set_csv(cast_csv(warm));
  }
  gram::KnownEnvironment held;
  ASSERT_TRUE(stub_->UpdateEnvironment(context().get(), update, &held).ok());
  ASSERT_EQ(held.instances_size(), 2);

  // Each instance's TL, from the daemon.
  std::vector<gram::TransmissionLoss> fields;
  for (const auto& instance : held.instances()) {
    v1::TransmissionLossRequest request;
    *request.mutable_header()->mutable_environment()->mutable_sound_speed() = instance.sound_speed();
    v1::TransmissionLossReply reply;
    ASSERT_TRUE(stub_->TransmissionLoss(context().get(), request, &reply).ok());
    gram::TransmissionLoss tl;
    tl.range_m.assign(reply.range_m().begin(), reply.range_m().end());
    tl.depth_m.assign(reply.depth_m().begin(), reply.depth_m().end());
    tl.tl_db.assign(reply.tl_db().begin(), reply.tl_db().end());
    fields.push_back(tl);
  }

  const auto windows = read_csv("range_window_eq4_1.csv");
  const auto sonar_rows = read_csv("sonar_equation_eq4_7.csv");
  ASSERT_FALSE(windows.empty());
  ASSERT_FALSE(sonar_rows.empty());
  std::size_t checked = 0;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    const auto& row = windows[w];
    v1::DepthObjectiveRequest request;
    auto* q = request.mutable_query();
    q->set_range_m(3000);
    q->set_speed_mps(std::stod(row.at("speed_mps")));
    q->set_heading_deg(std::stod(row.at("theta_deg")));
    q->set_horizon_s(std::stod(row.at("tau_a_s")));
    q->set_h_max_db(108);
    q->mutable_limits()->set_min_depth_m(5);
    q->mutable_limits()->set_max_depth_m(90);
    q->mutable_limits()->set_min_altitude_m(5);
    q->mutable_lowpass()->set_cutoff_per_m(1.0 / 50);
    v1::DepthObjectiveResponse response;
    grpc::Status status = stub_->DepthObjective(context().get(), request, &response);
    ASSERT_TRUE(status.ok()) << status.error_message();
    const auto& r = response.reply();
    EXPECT_EQ(response.instances(), 2u);
    const double delta_r = std::stod(row.at("delta_r_m"));
    if (!r.window_widened()) {
      EXPECT_NEAR(r.window_end_m() - r.window_begin_m(), std::abs(delta_r), 1e-6) << "row " << w;
    }
    gram::RangeWindow window;
    window.begin_m = r.window_begin_m();
    window.end_m = r.window_end_m();
    window.widened = r.window_widened();
    std::vector<gram::RangeAveragedTl> per_instance;
    for (const auto& tl : fields) per_instance.push_back(gram::range_averaged_tl(tl, window));
    std::vector<double> depths, objective;
    for (int i = 0; i < r.points_size(); ++i) {
      const auto& p = r.points(i);
      const double h[2] = {per_instance[0].h_bar_db[i], per_instance[1].h_bar_db[i]};
      const auto expected = gram::average_over_instances(h);
      EXPECT_NEAR(p.h_bar_db(), expected.h_n_db, 1e-3) << "row " << w << " depth " << p.depth_m();
      EXPECT_NEAR(p.objective(), std::max(1 - expected.h_n_db / 108, 0.0), 1e-4);
      depths.push_back(p.depth_m());
      objective.push_back(p.objective());
      ++checked;
    }
    EXPECT_GE(r.best_depth_m(), 5);
    EXPECT_LE(r.best_depth_m(), 90);
  }
  EXPECT_GT(checked, 20u);

  // The sonar equation with the conformance file's band noise: NL as the
  // file, SE = SL − H̄ − NL + AG.
  for (const auto& row : sonar_rows) {
    v1::DepthObjectiveRequest request;
    auto* q = request.mutable_query();
    q->set_range_m(3000);
    q->set_speed_mps(1.5);
    q->set_horizon_s(120);
    q->mutable_limits()->set_max_depth_m(90);
    auto* s = q->mutable_sonar();
    s->set_source_level_db(std::stod(row.at("sl_db")));
    s->set_array_gain_db(std::stod(row.at("ag_db")));
    auto* band = s->mutable_noise_band();
    band->set_f_lo_khz(std::stod(row.at("f_lo_khz")));
    band->set_f_hi_khz(std::stod(row.at("f_hi_khz")));
    band->set_shipping(std::stod(row.at("shipping")));
    band->set_wind_mps(std::stod(row.at("wind_mps")));
    v1::DepthObjectiveResponse response;
    grpc::Status status = stub_->DepthObjective(context().get(), request, &response);
    ASSERT_TRUE(status.ok()) << status.error_message();
    for (const auto& p : response.reply().points()) {
      EXPECT_NEAR(p.noise_level_db(), std::stod(row.at("nl_db")), 1e-3);
      if (std::isfinite(p.h_bar_db())) {
        EXPECT_NEAR(p.signal_excess_db(),
                    std::stod(row.at("sl_db")) - p.h_bar_db() - p.noise_level_db() + std::stod(row.at("ag_db")), 1e-3);
      }
    }
  }

  // The causal low-pass of the objective over the allowed depths (§6.4).
  v1::DepthObjectiveRequest request;
  auto* q = request.mutable_query();
  q->set_range_m(3000);
  q->set_speed_mps(1.5);
  q->set_horizon_s(120);
  q->set_h_max_db(108);
  q->mutable_limits()->set_max_depth_m(1000);
  q->mutable_lowpass()->set_cutoff_per_m(1.0 / 50);
  v1::DepthObjectiveResponse response;
  ASSERT_TRUE(stub_->DepthObjective(context().get(), request, &response).ok());
  std::vector<double> depths, raw;
  for (const auto& p : response.reply().points()) {
    depths.push_back(p.depth_m());
    raw.push_back(p.objective());
  }
  const auto filtered = gram::lowpass_on_depths(depths, raw, {1.0 / 50, false});
  for (int i = 0; i < response.reply().points_size(); ++i)
    EXPECT_NEAR(response.reply().points(i).objective_filtered(), filtered[i], 1e-4) << "depth " << depths[i];

  // A query without a horizon is refused naming the field.
  request.mutable_query()->set_horizon_s(0);
  grpc::Status bad = stub_->DepthObjective(context().get(), request, &response);
  EXPECT_EQ(bad.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(bad.error_message().find("horizon_s"), std::string::npos) << bad.error_message();
}

// acommsctl's daemon commands: env update/show and depth (with --png).
TEST_F(GramServiceTest, AcommsctlFeedsTheEnvironmentAndPrintsTheBestDepth) {
  start();
  const std::string ctl = ACOMMSCTL_BINARY;
  const std::string cast = (dir_ / "cast.csv").string();
  std::ofstream(cast) << cast_csv(19);
  auto r = run(ctl, {"--socket", socket_, "gram", "env", "update", "--ctd", cast, "--time", "1700000000"},
               (dir_ / "ctl1").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1 profile instance(s) held"), std::string::npos) << r.out;
  r = run(ctl, {"--socket", socket_, "gram", "env", "show"}, (dir_ / "ctl2").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("time_s: 1700000000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("samples: 51"), std::string::npos) << r.out;

  const std::string png = (dir_ / "depth.png").string();
  r = run(ctl, {"--socket", socket_, "gram", "depth", "--range", "3000", "--speed", "1.5", "--max-depth", "90",
                "--min-altitude", "5", "--lowpass", "0.02", "--png", png},
          (dir_ / "ctl3").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("depth_m,h_bar_db,objective,objective_filtered\n", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("# best depth "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 profile instance(s)"), std::string::npos) << r.out;
  std::ifstream in(png, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");

  // The deep-water forecast strategy (issue 32): its plan after the table.
  r = run(ctl, {"--socket", socket_, "gram", "depth", "--range", "1000", "--speed", "1.5", "--max-depth", "90",
                "--min-altitude", "5", "--forecast-horizon", "600", "--current-depth", "20", "--vertical-speed", "0.5"},
          (dir_ / "ctl5").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("# forecast over 600 s (6 windows): "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; at the next window be at "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the plan's best point "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("first window at "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("# plan (depth at each window, m; mean score "), std::string::npos) << r.out;
  // "nan" is not a curve left unset: refused.
  r = run(ctl, {"--socket", socket_, "gram", "depth", "--range", "1000", "--speed", "1.5", "--max-depth", "90",
                "--source-level", "185", "--noise-level", "80", "--forecast-horizon", "600", "--reception-snr50", "nan"},
          (dir_ / "ctl8").string());
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.err.find("must be a finite number, not nan"), std::string::npos) << r.err;
  // The reception curve needs the sonar equation.
  r = run(ctl, {"--socket", socket_, "gram", "depth", "--range", "1000", "--speed", "1.5", "--max-depth", "90",
                "--forecast-horizon", "600", "--reception-snr50", "10"},
          (dir_ / "ctl7").string());
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.err.find("--reception-snr50 needs the sonar equation"), std::string::npos) << r.err;
  // Without the sonar equation the noise profile has nothing to act on.
  r = run(ctl, {"--socket", socket_, "gram", "depth", "--range", "1000", "--speed", "1.5", "--max-depth", "90",
                "--noise-decrease", "3"},
          (dir_ / "ctl6").string());
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.err.find("--noise-decrease needs the sonar equation"), std::string::npos) << r.err;

  // Refused by the daemon: exit 1 and the status name.
  r = run(ctl, {"--socket", socket_, "gram", "depth", "--range", "3000", "--speed", "1.5", "--max-depth", "90",
                "--horizon", "0"},
          (dir_ / "ctl4").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("INVALID_ARGUMENT"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("horizon_s"), std::string::npos) << r.err;
}

// The external engine through a stand-in: the run's title picks what the
// stand-in does (write the known field, hang, fail).
TEST_F(GramServiceTest, TheExternalEngineAnswersFailsVerbatimAndIsKilledWhenItHangs) {
  const fs::path script = dir_ / "bellhop.sh";
  std::ofstream(script) << "#!/bin/sh\n"
                        << "grep -q \"^'hang'\" \"$1.env\" && exec sleep 600\n"
                        << "if grep -q \"^'fail'\" \"$1.env\"; then echo 'BELLHOP: too many beams for this build' >&2; "
                           "exit 5; fi\n"
                        << "exec " << FAKE_BELLHOP << " --layout 2022 \"$@\"\n";
  fs::permissions(script, fs::perms::owner_all);
  write_config("engine: \"bellhop\" bellhop_path: \"" + script.string() + "\" engine_timeout_s: 1");
  start();

  v1::TransmissionLossRequest request;
  auto* env = request.mutable_header()->mutable_environment();
  env->set_title("known");
  v1::TransmissionLossReply reply;
  grpc::Status status = stub_->TransmissionLoss(context().get(), request, &reply);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(reply.engine(), "bellhop");
  ASSERT_EQ(reply.tl_db_size(), 25 * 393);
  for (int iz = 0; iz < 25; iz += 6)
    for (int ir = 0; ir < 393; ir += 50)
      EXPECT_NEAR(reply.tl_db(iz * 393 + ir), 20 * std::log10(reply.range_m(ir)) + reply.depth_m(iz) / 10, 1e-4);

  env->set_title("fail");
  status = stub_->TransmissionLoss(context().get(), request, &reply);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INTERNAL);
  EXPECT_NE(status.error_message().find("BELLHOP: too many beams for this build"), std::string::npos)
      << status.error_message();

  env->set_title("hang");
  status = stub_->TransmissionLoss(context().get(), request, &reply);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INTERNAL);
  EXPECT_NE(status.error_message().find("engine_timeout_s = 1"), std::string::npos) << status.error_message();
  // The worker is free: the next run is answered.
  env->set_title("known again");
  EXPECT_TRUE(stub_->TransmissionLoss(context().get(), request, &reply).ok());
  EXPECT_FALSE(fs::exists(dir_ / "data" / "gram-runs") && !fs::is_empty(dir_ / "data" / "gram-runs"));
}

}  // namespace
}  // namespace acomms::testing
