// The store: migrations applied once, in order, in one transaction; WAL mode;
// clear refusals for newer schemas, corrupt files and unusable data dirs.

#include "store/store.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace acomms::store {
namespace {

namespace fs = std::filesystem;

class StoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("acomms_store_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string error_opening(const std::string& dir) {
    try {
      Store store(dir);
    } catch (const StoreError& e) {
      return e.what();
    }
    ADD_FAILURE() << "store opened without error";
    return "";
  }

  fs::path dir_;
};

int64_t count(Database& db, const char* sql) {
  Statement query = db.prepare(sql);
  query.step();
  return query.column_int64(0);
}

TEST_F(StoreTest, NewStoreAppliesEveryMigrationOnce) {
  const auto& migrations = known_migrations();
  ASSERT_FALSE(migrations.empty());
  {
    Store store(dir_.string());
    EXPECT_EQ(store.migration().from_version, 0);
    EXPECT_EQ(store.migration().applied, static_cast<int>(migrations.size()));
    EXPECT_EQ(store.schema_version(), migrations.back().version);
    EXPECT_EQ(count(store.db(), "SELECT count(*) FROM schema_migrations"),
              static_cast<int64_t>(migrations.size()));
    Statement mode = store.db().prepare("PRAGMA journal_mode");
    mode.step();
    EXPECT_EQ(mode.column_text(0), "wal");
  }
  Store again(dir_.string());
  EXPECT_EQ(again.migration().applied, 0);
  EXPECT_EQ(again.migration().from_version, migrations.back().version);
  EXPECT_EQ(count(again.db(), "SELECT count(*) FROM schema_migrations"),
            static_cast<int64_t>(migrations.size()));
}

TEST_F(StoreTest, MigrationsAreNumberedInOrder) {
  int64_t previous = 0;
  for (const Migration& m : known_migrations()) {
    EXPECT_GT(m.version, previous) << m.name;
    EXPECT_EQ(std::stoll(m.name.substr(0, 4)), m.version);
    previous = m.version;
  }
}

TEST_F(StoreTest, NewerSchemaIsRefusedAndLeftUntouched) {
  { Store store(dir_.string()); }
  {
    Database db((dir_ / kStoreFileName).string());
    db.exec("INSERT INTO schema_migrations VALUES (9999, '9999_future.sql', 'later')");
  }
  std::string error = error_opening(dir_.string());
  EXPECT_NE(error.find("schema version 9999"), std::string::npos) << error;
  EXPECT_NE(error.find("newer"), std::string::npos) << error;
  Database db((dir_ / kStoreFileName).string());
  EXPECT_EQ(count(db, "SELECT max(version) FROM schema_migrations"), 9999);
}

TEST_F(StoreTest, CorruptFileIsAClearError) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / kStoreFileName) << std::string(8192, 'x');
  std::string error = error_opening(dir_.string());
  EXPECT_NE(error.find("not a usable SQLite database"), std::string::npos) << error;
  EXPECT_NE(error.find((dir_ / kStoreFileName).string()), std::string::npos) << error;
}

TEST_F(StoreTest, DataDirThatIsAFileIsAClearError) {
  std::ofstream(dir_.string()) << "not a dir";
  std::string error = error_opening((dir_ / "sub").string());
  EXPECT_NE(error.find("cannot create"), std::string::npos) << error;
  fs::remove(dir_);
}

TEST_F(StoreTest, StoreFileThatIsADirectoryIsAClearError) {
  fs::create_directories(dir_ / kStoreFileName);
  std::string error = error_opening(dir_.string());
  EXPECT_NE(error.find(kStoreFileName), std::string::npos) << error;
}

TEST_F(StoreTest, ReadOnlyStoreFileIsAClearError) {
  { Store store(dir_.string()); }
  // The dir stays writable (lock and WAL files can be made); only the
  // database file is read-only. Root ignores file modes, so a root test run
  // checks this as "nobody" in a child process.
  fs::permissions(dir_, fs::perms::all);
  fs::permissions(dir_ / kStoreFileName, fs::perms::owner_read | fs::perms::group_read |
                                             fs::perms::others_read);
  fs::remove(dir_ / "acommsd.lock");
  EXPECT_EXIT(
      {
        if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) std::exit(3);
        try {
          Store store(dir_.string());
        } catch (const StoreError& e) {
          std::fprintf(stderr, "%s\n", e.what());
          std::exit(0);
        }
        std::exit(1);
      },
      ::testing::ExitedWithCode(0), "is read-only: .* writable by this user");
}

TEST_F(StoreTest, SecondStoreOnTheSameDirIsRefused) {
  Store first(dir_.string());
  std::string error = error_opening(dir_.string());
  EXPECT_NE(error.find("in use by another acommsd"), std::string::npos) << error;
}

TEST_F(StoreTest, FailedMigrationKeepsNothing) {
  fs::create_directories(dir_);
  Database db((dir_ / "m.db").string());
  std::vector<Migration> migrations = {
      {1, "0001_ok.sql", "CREATE TABLE a (x INTEGER)"},
      {2, "0002_broken.sql", "CREATE TABLE b (x INTEGER); THIS IS NOT SQL"},
  };
  try {
    migrate(db, migrations);
    FAIL() << "no error";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("migration 0002_broken.sql failed"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(schema_version(db), 0);
  EXPECT_EQ(count(db, "SELECT count(*) FROM sqlite_master WHERE name IN ('a', 'b')"), 0);

  migrations.pop_back();
  MigrationReport report = migrate(db, migrations);
  EXPECT_EQ(report.applied, 1);
  EXPECT_EQ(schema_version(db), 1);
}

}  // namespace
}  // namespace acomms::store
