// DefinitionLoader (daemon/node/definition_loader.h): inline definitions
// written under the inline dir and loaded, queues made for the new types,
// names that would leave the inline dir refused, types that cannot change,
// missing and broken files, and the record in loaded_definitions that
// brings them back at the next start.

#include "node/definition_loader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/clock.h"
#include "queue/memory_journal.h"
#include "store/store.h"

namespace acomms::node {
namespace {

namespace fs = std::filesystem;

std::string proto(const std::string& package, const std::string& message, int id, int max = 100) {
  return "syntax = \"proto2\";\n"
         "import \"dccl/option_extensions.proto\";\n"
         "package " + package + ";\n"
         "message " + message + " {\n"
         "  option (dccl.msg) = { codec_version: 4 id: " + std::to_string(id) + " max_bytes: 16 };\n"
         "  required int32 value = 1 [(dccl.field) = { min: 0 max: " + std::to_string(max) + " }];\n"
         "}\n";
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class DefinitionLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("acomms-defs-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    store_ = std::make_unique<store::Store>((dir_ / "data").string());
    writer_ = std::make_unique<store::GroupCommitWriter>(store_->db());
    queues_ = std::make_unique<queue::QueueManager>(codec_, v1::QueueConfig(), 1, clock_, journal_);
    loader_ = std::make_unique<DefinitionLoader>(codec_, *queues_, *writer_, inline_dir().string());
  }
  void TearDown() override {
    loader_.reset();
    queues_.reset();
    writer_.reset();
    store_.reset();
    fs::remove_all(dir_);
  }

  fs::path inline_dir() const { return dir_ / "data" / "definitions"; }

  // Loads one inline definition; returns the loaded type names.
  std::vector<std::string> load_inline(const std::string& name, const std::string& text,
                                       const std::vector<std::string>& include_dirs = {}) {
    v1::LoadDefinitionsRequest request;
    auto* definition = request.add_inline_();
    definition->set_name(name);
    definition->set_text(text);
    for (const auto& dir : include_dirs) request.add_include_dirs(dir);
    return names(loader_->load(request));
  }
  std::vector<std::string> load_path(const std::string& path, const std::vector<std::string>& include_dirs = {}) {
    v1::LoadDefinitionsRequest request;
    request.add_paths(path);
    for (const auto& dir : include_dirs) request.add_include_dirs(dir);
    return names(loader_->load(request));
  }
  static std::vector<std::string> names(const std::vector<const dccl::TypeInfo*>& types) {
    std::vector<std::string> out;
    for (const auto* info : types) out.push_back(info->name);
    return out;
  }

  // The DefinitionError `load` throws (fails the test if none).
  template <typename Load>
  DefinitionError error_of(Load load) {
    try {
      load();
    } catch (const DefinitionError& e) {
      return e;
    }
    ADD_FAILURE() << "no DefinitionError";
    return DefinitionError(DefinitionError::Code::kStore, "<none>");
  }

  // What the store recorded (the writer is stopped first: then the
  // connection is ours again).
  std::vector<RecordedDefinition> recorded() {
    writer_->stop();
    return DefinitionLoader::read_recorded(store_->db());
  }

  size_t queue_count() const { return queues_->queues().size(); }

  fs::path dir_;
  dccl::Codec codec_;
  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  queue::MemoryJournal journal_;
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<store::GroupCommitWriter> writer_;
  std::unique_ptr<queue::QueueManager> queues_;
  std::unique_ptr<DefinitionLoader> loader_;
};

TEST_F(DefinitionLoaderTest, InlineDefinitionIsWrittenUnderTheInlineDirLoadedAndQueued) {
  EXPECT_EQ(loader_->inline_dir(), inline_dir().string());
  const std::string text = proto("mission", "Ping", 30);
  EXPECT_EQ(load_inline("mission.proto", text), std::vector<std::string>{"mission.Ping"});
  EXPECT_EQ(read(inline_dir() / "mission.proto"), text);
  EXPECT_NE(codec_.find_type("mission.Ping"), nullptr);
  EXPECT_NE(queues_->find_queue("mission.Ping"), nullptr) << "no queue for the new type";
  // Nothing half-written is left behind.
  for (const auto& entry : fs::recursive_directory_iterator(inline_dir())) {
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();
  }
}

TEST_F(DefinitionLoaderTest, InlineNamesMayHaveSubdirectories) {
  EXPECT_EQ(load_inline("fleet/a-1_v2.proto", proto("fleet", "A", 31)), std::vector<std::string>{"fleet.A"});
  EXPECT_TRUE(fs::is_regular_file(inline_dir() / "fleet" / "a-1_v2.proto"));
}

TEST_F(DefinitionLoaderTest, InlineDefinitionsMayImportEachOther) {
  v1::LoadDefinitionsRequest request;
  auto* base = request.add_inline_();
  base->set_name("base.proto");
  base->set_text("syntax = \"proto2\";\npackage base;\nenum Kind { A = 1; B = 2; }\n");
  auto* user = request.add_inline_();
  user->set_name("user.proto");
  user->set_text(
      "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\nimport \"base.proto\";\npackage user;\n"
      "message U {\n  option (dccl.msg) = { codec_version: 4 id: 32 max_bytes: 8 };\n"
      "  required base.Kind kind = 1;\n}\n");
  EXPECT_EQ(names(loader_->load(request)), std::vector<std::string>{"user.U"});
}

TEST_F(DefinitionLoaderTest, SameInlineTextAgainIsHarmlessOtherTextIsRefused) {
  const std::string text = proto("mission", "Ping", 30);
  load_inline("mission.proto", text);
  size_t queues = queue_count();
  EXPECT_NO_THROW(load_inline("mission.proto", text));
  EXPECT_EQ(queue_count(), queues);

  DefinitionError e = error_of([&] { load_inline("mission.proto", proto("mission", "Ping", 30, 50)); });
  EXPECT_EQ(e.code, DefinitionError::Code::kInvalid);
  EXPECT_NE(std::string(e.what()).find("types cannot change"), std::string::npos) << e.what();
  EXPECT_EQ(read(inline_dir() / "mission.proto"), text) << "the refused text replaced the loaded one";
  EXPECT_EQ(queue_count(), queues);

  // A new version under another name is fine.
  EXPECT_EQ(load_inline("mission2.proto", proto("mission2", "Ping", 33, 50)),
            std::vector<std::string>{"mission2.Ping"});
}

TEST_F(DefinitionLoaderTest, InlineNamesThatLeaveTheInlineDirAreRefused) {
  for (const std::string name : {"../evil.proto", "a/../../evil.proto", "..", "sub/../../../evil.proto"}) {
    DefinitionError e = error_of([&] { load_inline(name, proto("evil", "E", 40)); });
    EXPECT_EQ(e.code, DefinitionError::Code::kInvalid) << name;
    EXPECT_NE(std::string(e.what()).find(".."), std::string::npos) << e.what();
  }
  std::string absolute = (dir_ / "abs.proto").string();
  DefinitionError e = error_of([&] { load_inline(absolute, proto("evil", "E", 40)); });
  EXPECT_EQ(e.code, DefinitionError::Code::kInvalid);
  EXPECT_FALSE(fs::exists(absolute)) << "an absolute inline name was written";
  EXPECT_FALSE(fs::exists(dir_ / "data" / "evil.proto"));
  EXPECT_FALSE(fs::exists(dir_ / "evil.proto"));
  EXPECT_EQ(codec_.find_type("evil.E"), nullptr);

  for (const std::string name : {"", "bad name.proto", "semi;colon.proto", "back\\slash.proto"}) {
    EXPECT_EQ(error_of([&] { load_inline(name, proto("evil", "E", 40)); }).code, DefinitionError::Code::kInvalid)
        << "\"" << name << "\"";
  }
  EXPECT_TRUE(recorded().empty());
}

TEST_F(DefinitionLoaderTest, MissingPathIsNotFound) {
  DefinitionError e = error_of([&] { load_path((dir_ / "nope.proto").string()); });
  EXPECT_EQ(e.code, DefinitionError::Code::kNotFound);
  EXPECT_NE(std::string(e.what()).find("nope.proto"), std::string::npos) << e.what();
  DefinitionError relative = error_of([&] { load_path("nope/relative.proto", {(dir_ / "inc").string()}); });
  EXPECT_EQ(relative.code, DefinitionError::Code::kNotFound);
  EXPECT_NE(std::string(relative.what()).find((dir_ / "inc").string()), std::string::npos)
      << "does not say where it looked: " << relative.what();
}

TEST_F(DefinitionLoaderTest, EmptyRequestIsInvalid) {
  DefinitionError e = error_of([&] { loader_->load(v1::LoadDefinitionsRequest()); });
  EXPECT_EQ(e.code, DefinitionError::Code::kInvalid);
}

TEST_F(DefinitionLoaderTest, BrokenProtoIsInvalidWithFileAndLine) {
  std::ofstream(dir_ / "bad.proto") << "syntax = \"proto2\";\n"
                                       "package bad;\n"
                                       "message Bad {\n"
                                       "  required int32 x = 1 oops;\n"
                                       "}\n";
  DefinitionError e = error_of([&] { load_path((dir_ / "bad.proto").string()); });
  EXPECT_EQ(e.code, DefinitionError::Code::kInvalid);
  EXPECT_NE(std::string(e.what()).find("bad.proto:4:"), std::string::npos) << e.what();

  DefinitionError inline_error = error_of([&] { load_inline("broken.proto", "syntax = \"proto2\";\nmessage {\n"); });
  EXPECT_EQ(inline_error.code, DefinitionError::Code::kInvalid);
  EXPECT_NE(std::string(inline_error.what()).find("broken.proto:2:"), std::string::npos) << inline_error.what();
  EXPECT_TRUE(recorded().empty()) << "a file that did not load was recorded";
}

TEST_F(DefinitionLoaderTest, DcclRuleViolationIsInvalid) {
  // Parses as protobuf, breaks a DCCL rule (string without max_length).
  std::string text =
      "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage rule;\n"
      "message R {\n  option (dccl.msg) = { codec_version: 4 id: 41 max_bytes: 8 };\n"
      "  required string s = 1;\n}\n";
  DefinitionError e = error_of([&] { load_inline("rule.proto", text); });
  EXPECT_EQ(e.code, DefinitionError::Code::kInvalid);
  EXPECT_NE(std::string(e.what()).find("rule.R.s"), std::string::npos) << e.what();
  EXPECT_EQ(codec_.find_type("rule.R"), nullptr);
}

// An inline definition that failed to load was never loaded: sending it
// again corrected, under the same name, must work (there is no type of
// that name whose layout could change).
TEST_F(DefinitionLoaderTest, InlineDefinitionThatFailedToLoadCanBeCorrected) {
  std::string broken = "syntax = \"proto2\";\nmessage {\n";
  EXPECT_EQ(error_of([&] { load_inline("fixme.proto", broken); }).code, DefinitionError::Code::kInvalid);
  std::vector<std::string> types;
  try {
    types = load_inline("fixme.proto", proto("fixme", "F", 42));
  } catch (const DefinitionError& e) {
    FAIL() << "the corrected definition was refused: " << e.what();
  }
  EXPECT_EQ(types, std::vector<std::string>{"fixme.F"});
  EXPECT_NE(queues_->find_queue("fixme.F"), nullptr);
}

// A file on disk that failed to load, then fixed by the operator, loads
// when asked again (nothing of it was loaded the first time).
TEST_F(DefinitionLoaderTest, FileFixedOnDiskAfterAFailedLoadLoads) {
  std::ofstream(dir_ / "later.proto") << "syntax = \"proto2\";\nmessage {\n";
  EXPECT_EQ(error_of([&] { load_path((dir_ / "later.proto").string()); }).code, DefinitionError::Code::kInvalid);
  std::ofstream(dir_ / "later.proto", std::ios::trunc) << proto("later", "L", 43);
  std::vector<std::string> types;
  try {
    types = load_path((dir_ / "later.proto").string());
  } catch (const DefinitionError& e) {
    FAIL() << "the fixed file was refused: " << e.what();
  }
  EXPECT_EQ(types, std::vector<std::string>{"later.L"});
}

// A file that parses but breaks a DCCL rule (a numeric field without
// bounds, the usual slip at sea) is fixed and loaded again, inline under the
// same name and on disk at the same path.
TEST_F(DefinitionLoaderTest, DefinitionCorrectedAfterADcclRuleErrorLoads) {
  std::string unbounded = proto("slip", "S", 44);
  unbounded.replace(unbounded.find(" [(dccl.field)"), unbounded.find(";\n}") - unbounded.find(" [(dccl.field)"), "");
  DefinitionError inline_error = error_of([&] { load_inline("slip.proto", unbounded); });
  EXPECT_EQ(inline_error.code, DefinitionError::Code::kInvalid);
  EXPECT_NE(std::string(inline_error.what()).find("slip.S.value: numeric field needs"), std::string::npos)
      << inline_error.what();
  EXPECT_EQ(load_inline("slip.proto", proto("slip", "S", 44)), std::vector<std::string>{"slip.S"});
  EXPECT_NE(queues_->find_queue("slip.S"), nullptr);

  std::string on_disk = unbounded;
  on_disk.replace(on_disk.find("package slip;"), 13, "package disk;");
  on_disk.replace(on_disk.find("id: 44"), 6, "id: 45");
  std::ofstream(dir_ / "disk.proto") << on_disk;
  EXPECT_EQ(error_of([&] { load_path((dir_ / "disk.proto").string()); }).code, DefinitionError::Code::kInvalid);
  std::ofstream(dir_ / "disk.proto", std::ios::trunc) << proto("disk", "S", 45);
  EXPECT_EQ(load_path((dir_ / "disk.proto").string()), std::vector<std::string>{"disk.S"});
  EXPECT_EQ(recorded().size(), 2u);
}

// A loaded file edited on disk is refused by name, not silently kept in
// its old form; the loaded version and its record stay.
TEST_F(DefinitionLoaderTest, FileChangedAfterLoadingIsRefused) {
  std::string path = (dir_ / "edited.proto").string();
  std::ofstream(path) << proto("edited", "E", 46, 100);
  load_path(path);
  std::ofstream(path, std::ios::trunc) << proto("edited", "E", 46, 1000);
  DefinitionError e = error_of([&] { load_path(path); });
  EXPECT_EQ(e.code, DefinitionError::Code::kInvalid);
  EXPECT_NE(std::string(e.what()).find("edited.proto"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("has changed since it was loaded"), std::string::npos) << e.what();
  EXPECT_EQ(recorded().size(), 1u);
  EXPECT_NE(codec_.find_type("edited.E"), nullptr);
}

TEST_F(DefinitionLoaderTest, AddTypesMakesQueuesOnlyForTheNewTypes) {
  load_inline("one.proto", proto("one", "A", 50));
  ASSERT_EQ(queue_count(), 1u);
  const queue::Queue* first = queues_->find_queue("one.A");
  std::string two = "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage two;\n"
                    "message B {\n  option (dccl.msg) = { codec_version: 4 id: 51 max_bytes: 8 };\n"
                    "  required int32 v = 1 [(dccl.field) = { min: 0 max: 3 }];\n}\n"
                    "message C {\n  option (dccl.msg) = { codec_version: 4 id: 52 max_bytes: 8 };\n"
                    "  required int32 v = 1 [(dccl.field) = { min: 0 max: 3 }];\n}\n";
  std::vector<std::string> loaded = load_inline("two.proto", two);
  std::sort(loaded.begin(), loaded.end());
  EXPECT_EQ(loaded, (std::vector<std::string>{"two.B", "two.C"}));
  EXPECT_EQ(queue_count(), 3u);
  EXPECT_EQ(queues_->find_queue("one.A"), first) << "the existing queue was replaced";
}

TEST_F(DefinitionLoaderTest, LoadedFilesAreRecordedInOrderOnceAndLoadIntoAFreshCodec) {
  fs::create_directories(dir_ / "inc");
  std::ofstream(dir_ / "inc" / "disk.proto") << proto("disk", "D", 60);
  std::ofstream(dir_ / "abs.proto") << proto("abs", "Abs", 61);
  load_path("disk.proto", {(dir_ / "inc").string()});
  load_inline("inl.proto", proto("inl", "I", 62));
  load_path((dir_ / "abs.proto").string());
  // Loading again records nothing new.
  load_path("disk.proto", {(dir_ / "inc").string()});
  load_inline("inl.proto", proto("inl", "I", 62));

  std::vector<RecordedDefinition> rows = recorded();
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].path, "disk.proto");
  EXPECT_EQ(rows[0].include_dirs, std::vector<std::string>{(dir_ / "inc").string()});
  EXPECT_EQ(rows[1].path, fs::absolute(inline_dir() / "inl.proto").string());
  ASSERT_FALSE(rows[1].include_dirs.empty());
  EXPECT_EQ(rows[1].include_dirs[0], inline_dir().string());
  EXPECT_EQ(rows[2].path, (dir_ / "abs.proto").string());
  EXPECT_TRUE(rows[2].include_dirs.empty());

  dccl::Codec fresh;
  DefinitionLoader::load_recorded(fresh, rows);
  for (const char* type : {"disk.D", "inl.I", "abs.Abs"}) EXPECT_NE(fresh.find_type(type), nullptr) << type;
}

TEST_F(DefinitionLoaderTest, RecordedFileThatNoLongerLoadsIsSkipped) {
  std::ofstream(dir_ / "gone.proto") << proto("gone", "G", 70);
  load_path((dir_ / "gone.proto").string());
  load_inline("kept.proto", proto("kept", "K", 71));
  std::vector<RecordedDefinition> rows = recorded();
  ASSERT_EQ(rows.size(), 2u);
  fs::remove(dir_ / "gone.proto");
  dccl::Codec fresh;
  EXPECT_NO_THROW(DefinitionLoader::load_recorded(fresh, rows));
  EXPECT_EQ(fresh.find_type("gone.G"), nullptr);
  EXPECT_NE(fresh.find_type("kept.K"), nullptr);
}

TEST_F(DefinitionLoaderTest, RecordSurvivesReopeningTheStore) {
  load_inline("persist.proto", proto("persist", "P", 80));
  loader_.reset();
  queues_.reset();
  writer_.reset();
  store_.reset();
  store::Store reopened((dir_ / "data").string());
  std::vector<RecordedDefinition> rows = DefinitionLoader::read_recorded(reopened.db());
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].path, fs::absolute(inline_dir() / "persist.proto").string());
}

}  // namespace
}  // namespace acomms::node
