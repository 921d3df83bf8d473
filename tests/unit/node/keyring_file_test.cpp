// The auth keyring file (node/keyring_file.h) and the auth section's set-up
// (node/auth_setup.h): every bad input is a clear error naming the file (or
// field) and what to fix, and a SIGHUP reload that fails keeps the keys.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "node/auth_setup.h"
#include "node/keyring_file.h"
#include "temp_dir.h"

namespace acomms::node {
namespace {

using ::testing::HasSubstr;

const std::string kKey1 = "000102030405060708090a0b0c0d0e0f";
const std::string kKey2 = "00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff";

class KeyringFileTest : public ::testing::Test {
 protected:
  std::string write(const std::string& text, mode_t mode = 0600) {
    std::string path = (dir_ / "keyring").string();
    std::ofstream(path) << text;
    ::chmod(path.c_str(), mode);
    return path;
  }
  std::string error_of(const std::string& text, mode_t mode = 0600) {
    const std::string path = write(text, mode);
    try {
      read_keyring_file(path);
    } catch (const std::runtime_error& e) {
      EXPECT_THAT(e.what(), HasSubstr("auth.keyring_file " + path + ": "));
      return e.what();
    }
    return "";
  }
  acomms::testing::TempDir dir_{"keyring"};
};

TEST_F(KeyringFileTest, ReadsKeysTheirRetirementAndTheSignId) {
  dccl::Keyring ring = read_keyring_file(
      write("# fleet keys\n\nkey 1 " + kKey1 + " until 2026-12-01T00:00:00Z\n  key 2 " + kKey2 + "\nsign 2\n"));
  ASSERT_EQ(ring.keys.size(), 2u);
  EXPECT_EQ(ring.keys.at(1).key.size(), 16u);
  EXPECT_EQ(ring.keys.at(1).key[15], '\x0f');
  EXPECT_EQ(ring.keys.at(1).accept_until, 1'796'083'200.0);
  EXPECT_EQ(ring.keys.at(2).key.size(), 32u);
  EXPECT_FALSE(ring.keys.at(2).accept_until.has_value());
  EXPECT_EQ(ring.sign_id, 2);
}

TEST_F(KeyringFileTest, FileOpenToGroupOrOthersIsRefused) {
  EXPECT_THAT(error_of("key 1 " + kKey1 + "\nsign 1\n", 0640),
              HasSubstr("is open to group or others (mode 0640): keys must be readable only by the daemon's user "
                        "(chmod 600)"));
  EXPECT_THAT(error_of("key 1 " + kKey1 + "\nsign 1\n", 0604), HasSubstr("mode 0604"));
  EXPECT_EQ(error_of("key 1 " + kKey1 + "\nsign 1\n", 0400), "");
}

TEST_F(KeyringFileTest, MissingFileIsRefused) {
  EXPECT_THROW(read_keyring_file((dir_ / "absent").string()), std::runtime_error);
  try {
    read_keyring_file((dir_ / "absent").string());
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("absent: cannot read: No such file or directory"));
  }
}

TEST_F(KeyringFileTest, EachBadLineIsNamed) {
  EXPECT_THAT(error_of("key 1 0011\nsign 1\n"), HasSubstr("line 1: key 1 is 2 bytes: an AES key is 16, 24 or 32 bytes"));
  EXPECT_THAT(error_of("key 1 " + kKey1 + "0\nsign 1\n"), HasSubstr("line 1: key 1 needs its key in hex"));
  EXPECT_THAT(error_of("key 1 zz" + kKey1.substr(2) + "\nsign 1\n"), HasSubstr("line 1: key 1 needs its key in hex"));
  EXPECT_THAT(error_of("key 256 " + kKey1 + "\nsign 1\n"), HasSubstr("line 1: key needs an id from 0 to 255"));
  EXPECT_THAT(error_of("key 1 " + kKey1 + " until tomorrow\nsign 1\n"),
              HasSubstr("line 1: after the key, only `until YYYY-MM-DDTHH:MM:SSZ` may follow"));
  EXPECT_THAT(error_of("key 1 " + kKey1 + "\nkey 1 " + kKey1 + "\nsign 1\n"), HasSubstr("line 2: key 1 is given twice"));
  EXPECT_THAT(error_of("key 1 " + kKey1 + "\nsign 3\n"), HasSubstr("sign 3: no key with that id"));
  EXPECT_THAT(error_of("key 1 " + kKey1 + "\n"), HasSubstr("no `sign <id>` line"));
  EXPECT_THAT(error_of("kee 1 " + kKey1 + "\nsign 1\n"), HasSubstr("line 1: \"kee\" is not `key` or `sign`"));
  EXPECT_THAT(error_of("sign 1\n"), HasSubstr("the keyring holds no key"));
}

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package ka;
message Command {
  option (dccl.msg) = { codec_version: 4 id: 5 max_bytes: 32 };
  optional int32 value = 1 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

class AuthSetupTest : public KeyringFileTest {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "ka.proto") << kProto;
    codec_.load((dir_ / "ka.proto").string());
  }
  v1::AuthConfig config(const std::string& keyring, int tag_bits = 64) {
    v1::AuthConfig auth;
    auth.set_keyring_file(keyring);
    auth.set_tag_bits(tag_bits);
    v1::AuthenticatedType* type = auth.add_type();
    type->set_type("ka.Command");
    type->set_window_s(600);
    return auth;
  }
  std::string error_of_setup(const v1::AuthConfig& auth) {
    try {
      make_authenticator(auth, codec_, 1);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  dccl::Codec codec_;
};

TEST_F(AuthSetupTest, BadSectionsAreStartUpErrorsNamingTheField) {
  const std::string keyring = write("key 1 " + kKey1 + "\nsign 1\n");
  EXPECT_THAT(error_of_setup(config(keyring, 24)), HasSubstr("auth.tag_bits 24: must be 32 to 64"));
  EXPECT_THAT(error_of_setup(config("")), HasSubstr("auth.type is listed but auth.keyring_file is not set"));
  v1::AuthConfig unknown = config(keyring);
  unknown.mutable_type(0)->set_type("ka.Nothing");
  EXPECT_THAT(error_of_setup(unknown), HasSubstr("authenticated type ka.Nothing is not loaded"));
  EXPECT_EQ(make_authenticator(v1::AuthConfig(), codec_, 1), nullptr) << "no section: nothing authenticated";
  EXPECT_FALSE(codec_.authenticated("ka.Command"));
  auto authenticator = make_authenticator(config(keyring, 32), codec_, 1);
  ASSERT_NE(authenticator, nullptr);
  EXPECT_EQ(authenticator->trailer_bytes(), 10u);
  EXPECT_TRUE(codec_.authenticated("ka.Command"));
}

TEST_F(AuthSetupTest, ReloadTakesNewKeysAndKeepsTheOldOnesWhenTheFileIsBad) {
  const std::string keyring = write("key 1 " + kKey1 + "\nsign 1\n");
  auto authenticator = make_authenticator(config(keyring), codec_, 1);
  ASSERT_NE(authenticator, nullptr);
  write("key 1 " + kKey1 + "\nkey 2 " + kKey2 + "\nsign 2\n");
  EXPECT_TRUE(reload_keyring(config(keyring), *authenticator));
  EXPECT_EQ(authenticator->keyring()->sign_id, 2);
  write("key 3 " + kKey1 + "\nsign 3\n", 0644);
  EXPECT_FALSE(reload_keyring(config(keyring), *authenticator));
  EXPECT_EQ(authenticator->keyring()->sign_id, 2);
  EXPECT_EQ(authenticator->keyring()->keys.size(), 2u);
}

}  // namespace
}  // namespace acomms::node
