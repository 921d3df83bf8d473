// Config parsing: a good file gives the settings and defaults; each kind of
// bad file gives a ConfigError naming the file, line, column and field.

#include "core/config_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/config_error.h"

namespace acomms::core {
namespace {

ConfigError parse_error(const std::string& text) {
  try {
    parse_config(text, "test.conf");
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no ConfigError for:\n" << text;
  return ConfigError("", 0, 0, "", "");
}

TEST(ConfigLoader, GoodFileGivesItsSettings) {
  v1::Config config = parse_config(R"(
    data_dir: "/tmp/acomms"
    log_level: DEBUG
    grpc {
      unix_socket: "/tmp/a.sock"
      tcp_listen: "127.0.0.1:50051"
      tls { cert_file: "/etc/s.pem" key_file: "/etc/s.key" client_ca_file: "/etc/ca.pem" }
    }
    driver { name: "udp" modem_id: 7 }
    mac { name: "polled" }
  )", "good.conf");
  EXPECT_EQ(config.data_dir(), "/tmp/acomms");
  EXPECT_EQ(config.log_level(), v1::DEBUG);
  EXPECT_EQ(config.grpc().unix_socket(), "/tmp/a.sock");
  EXPECT_EQ(config.grpc().tcp_listen(), "127.0.0.1:50051");
  EXPECT_EQ(config.grpc().tls().cert_file(), "/etc/s.pem");
  EXPECT_EQ(config.grpc().tls().key_file(), "/etc/s.key");
  EXPECT_EQ(config.grpc().tls().client_ca_file(), "/etc/ca.pem");
  EXPECT_FALSE(config.grpc().insecure_tcp());
  EXPECT_EQ(config.driver().name(), "udp");
  EXPECT_EQ(config.driver().modem_id(), 7u);
  EXPECT_EQ(config.mac().name(), "polled");
}

TEST(ConfigLoader, EmptyFileGivesDefaults) {
  v1::Config config = parse_config("", "empty.conf");
  EXPECT_EQ(config.data_dir(), kDefaultDataDir);
  EXPECT_EQ(config.grpc().unix_socket(), kDefaultUnixSocket);
  EXPECT_EQ(config.grpc().tcp_listen(), "");
  EXPECT_EQ(config.log_level(), v1::INFO);
  EXPECT_EQ(config.driver().name(), "sim");
  EXPECT_EQ(config.driver().modem_id(), 1u);
  EXPECT_EQ(config.mac().name(), "none");
}

// The printed example claims to show every default: hold it to that.
TEST(ConfigLoader, ExampleConfigParsesToTheDefaults) {
  v1::Config example = parse_config(example_config(), "example");
  v1::Config defaults = parse_config("", "empty");
  EXPECT_EQ(example.SerializeAsString(), defaults.SerializeAsString())
      << example.DebugString() << "\nvs\n" << defaults.DebugString();
  // And it documents every top-level setting.
  const auto* type = v1::Config::descriptor();
  for (int i = 0; i < type->field_count(); ++i) {
    EXPECT_NE(example_config().find(type->field(i)->name()), std::string_view::npos)
        << type->field(i)->name() << " is not in the example config";
  }
}

TEST(ConfigLoader, UnknownFieldNamesFileLineAndField) {
  ConfigError e = parse_error("data_dir: \"/x\"\n\ngrpc {\n  unix_sockett: \"/y\"\n}\n");
  EXPECT_EQ(e.file(), "test.conf");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.column(), 3);
  EXPECT_EQ(e.field(), "unix_sockett");
  EXPECT_NE(std::string(e.what()).find("test.conf:4:3: field 'unix_sockett'"), std::string::npos)
      << e.what();
  EXPECT_NE(e.problem().find("no field named \"unix_sockett\""), std::string::npos) << e.problem();
}

TEST(ConfigLoader, WrongValueTypeNamesTheField) {
  ConfigError e = parse_error("driver {\n  modem_id: abc\n}\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.field(), "modem_id");
  EXPECT_NE(e.problem().find("integer"), std::string::npos) << e.problem();
}

TEST(ConfigLoader, BadEnumValueNamesTheField) {
  ConfigError e = parse_error("log_level: LOUD\n");
  EXPECT_EQ(e.line(), 1);
  EXPECT_EQ(e.field(), "log_level");
  EXPECT_NE(e.problem().find("LOUD"), std::string::npos) << e.problem();
}

TEST(ConfigLoader, SyntaxErrorGivesItsLine) {
  ConfigError e = parse_error("grpc {\n  unix_socket: \"/y\"\n\nlog_level: INFO\n");
  EXPECT_GE(e.line(), 4);  // the parser notices the missing '}' at the end
  EXPECT_FALSE(e.problem().empty());
}

TEST(ConfigLoader, RepeatedSingularFieldIsAnError) {
  ConfigError e = parse_error("data_dir: \"/a\"\ndata_dir: \"/b\"\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.field(), "data_dir");
}

TEST(ConfigLoader, BadTcpAddressIsLocated) {
  ConfigError e = parse_error("log_level: INFO\ngrpc {\n  tcp_listen: \"localhost\"\n}\n");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), 3);
  EXPECT_EQ(e.field(), "grpc.tcp_listen");
  EXPECT_NE(e.problem().find("host:port"), std::string::npos) << e.problem();

  ConfigError port = parse_error("grpc { tcp_listen: \"127.0.0.1:70000\" }");
  EXPECT_EQ(port.field(), "grpc.tcp_listen");
  EXPECT_NE(port.problem().find("1 to 65535"), std::string::npos) << port.problem();
}

TEST(ConfigLoader, IPv6TcpAddressIsAccepted) {
  EXPECT_EQ(parse_config("grpc { tcp_listen: \"[::1]:50051\" insecure_tcp: true }", "v6")
                .grpc()
                .tcp_listen(),
            "[::1]:50051");
}

// A config from before TLS (tcp_listen alone) must not start serving
// plaintext to the network: the error names both ways forward.
TEST(ConfigLoader, TcpWithoutTlsOrInsecureTcpNamesBothFixes) {
  ConfigError e = parse_error("grpc {\n  tcp_listen: \"127.0.0.1:50051\"\n}\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.field(), "grpc.tcp_listen");
  EXPECT_NE(e.problem().find("tls { cert_file:"), std::string::npos) << e.problem();
  EXPECT_NE(e.problem().find("insecure_tcp: true"), std::string::npos) << e.problem();
}

TEST(ConfigLoader, PlaintextTcpIsAcceptedOnlyWhenAskedFor) {
  v1::Config config =
      parse_config("grpc { tcp_listen: \"127.0.0.1:50051\" insecure_tcp: true }", "plain");
  EXPECT_TRUE(config.grpc().insecure_tcp());
  EXPECT_FALSE(config.grpc().has_tls());
}

TEST(ConfigLoader, TlsNeedsCertAndKeyAndExcludesInsecureTcp) {
  ConfigError no_key = parse_error(
      "grpc {\n  tcp_listen: \"127.0.0.1:1\"\n  tls {\n    cert_file: \"/c.pem\"\n  }\n}\n");
  EXPECT_EQ(no_key.field(), "grpc.tls.key_file");
  EXPECT_NE(no_key.problem().find("required with tls"), std::string::npos) << no_key.problem();
  ConfigError no_cert = parse_error("grpc { tcp_listen: \"127.0.0.1:1\" tls { key_file: \"/k\" } }");
  EXPECT_EQ(no_cert.field(), "grpc.tls.cert_file");
  ConfigError both = parse_error(
      "grpc { tcp_listen: \"127.0.0.1:1\" insecure_tcp: true tls { cert_file: \"/c\" key_file: "
      "\"/k\" } }");
  EXPECT_EQ(both.field(), "grpc.insecure_tcp");
  EXPECT_NE(both.problem().find("not both"), std::string::npos) << both.problem();
}

TEST(ConfigLoader, TlsWithoutTcpListenIsRefused) {
  ConfigError e = parse_error("grpc { tls { cert_file: \"/c\" key_file: \"/k\" } }");
  EXPECT_EQ(e.field(), "grpc.tls");
  EXPECT_NE(e.problem().find("tcp_listen"), std::string::npos) << e.problem();
}

TEST(ConfigLoader, OverlongSocketPathIsRefused) {
  std::string path(200, 'a');
  ConfigError e = parse_error("grpc { unix_socket: \"/" + path + "\" }");
  EXPECT_EQ(e.field(), "grpc.unix_socket");
  EXPECT_NE(e.problem().find("at most 107"), std::string::npos) << e.problem();
}

// The auth section's mistakes are load errors naming the line and field.
TEST(ConfigLoader, AuthWindowOfZeroTagBitsOutOfRangeAndMissingKeyringAreRefused) {
  ConfigError zero = parse_error(
      "auth {\n  keyring_file: \"/k\"\n  type { type: \"a.B\" window_s: 60 }\n  type { type: \"a.C\" }\n}\n");
  EXPECT_EQ(zero.field(), "auth.type");
  EXPECT_EQ(zero.line(), 4);
  EXPECT_NE(zero.problem().find("a.C: window_s must be more than 0 seconds"), std::string::npos) << zero.problem();
  ConfigError bits = parse_error("auth {\n  tag_bits: 28\n}\n");
  EXPECT_EQ(bits.field(), "auth.tag_bits");
  EXPECT_EQ(bits.line(), 2);
  EXPECT_NE(bits.problem().find("must be 32 to 64, a multiple of 8"), std::string::npos) << bits.problem();
  ConfigError keyring = parse_error("auth { type { type: \"a.B\" window_s: 60 } }");
  EXPECT_EQ(keyring.field(), "auth.type");
  EXPECT_NE(keyring.problem().find("need auth.keyring_file"), std::string::npos) << keyring.problem();
}

TEST(ConfigLoader, BadDriverAndMacNamesAreRefused) {
  ConfigError driver = parse_error("driver { name: \"Sim Driver\" }");
  EXPECT_EQ(driver.field(), "driver.name");
  EXPECT_EQ(driver.line(), 1);
  ConfigError mac = parse_error("mac {\n name: \"../x\"\n}");
  EXPECT_EQ(mac.field(), "mac.name");
  EXPECT_EQ(mac.line(), 2);
}

TEST(ConfigLoader, NegativeEventRetentionIsRefusedNamingTheField) {
  ConfigError days = parse_error("store {\n event_retention_days: -1\n}");
  EXPECT_EQ(days.field(), "store.event_retention_days");
  EXPECT_EQ(days.line(), 2);
  EXPECT_NE(days.problem().find("0 (no age bound) or more"), std::string::npos) << days.problem();
  ConfigError mb = parse_error("store { event_retention_mb: -5 }");
  EXPECT_EQ(mb.field(), "store.event_retention_mb");
}

TEST(ConfigLoader, MissingFileIsNamed) {
  try {
    load_config_file("/nonexistent/acommsd.conf");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/acommsd.conf");
    EXPECT_EQ(std::string(e.what()), "/nonexistent/acommsd.conf: cannot open config file");
  }
}

TEST(ConfigLoader, FileErrorsCarryThePath) {
  auto path = std::filesystem::temp_directory_path() / "acomms_config_test.conf";
  std::ofstream(path) << "log_level: INFO\nbogus: 1\n";
  try {
    load_config_file(path.string());
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.field(), "bogus");
  }
  std::filesystem::remove(path);
}

TEST(ConfigLoader, EffectiveConfigChecksOverrides) {
  v1::Config config = parse_config("", "x");
  EXPECT_NO_THROW(check_effective_config(config));
  config.mutable_grpc()->set_unix_socket("/" + std::string(120, 's'));
  EXPECT_THROW(check_effective_config(config), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::core
