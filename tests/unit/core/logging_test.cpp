// configure_logging (daemon/core/logging.h): libprotobuf's own messages come
// out through the daemon's logger, in its format and under its level.

#include "core/logging.h"

#include <google/protobuf/descriptor.pb.h>
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

namespace acomms::core {
namespace {

// A FileDescriptorProto whose name (a proto2 string) is not UTF-8: parsing
// it makes libprotobuf log an ERROR.
std::string not_utf8_name() { return std::string("\x0a\x02\xff\xfe", 4); }

std::string log_of_parse(v1::LogLevel level) {
  configure_logging(level);
  ::testing::internal::CaptureStderr();
  google::protobuf::FileDescriptorProto parsed;
  (void)parsed.ParseFromString(not_utf8_name());
  spdlog::default_logger()->flush();
  return ::testing::internal::GetCapturedStderr();
}

TEST(LoggingTest, ProtobufMessagesAreWarningsOfTheDaemonsLogger) {
  std::string out = log_of_parse(v1::INFO);
  EXPECT_NE(out.find("[warning] protobuf: String field 'google.protobuf.FileDescriptorProto.name' contains "
                     "invalid UTF-8"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("[libprotobuf ERROR"), std::string::npos) << out;
}

TEST(LoggingTest, ProtobufMessagesFollowTheConfiguredLevel) {
  EXPECT_EQ(log_of_parse(v1::ERROR), "");
  configure_logging(v1::INFO);
}

}  // namespace
}  // namespace acomms::core
