#include "core/logging.h"

#include <google/protobuf/stubs/logging.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

namespace acomms::core {
namespace {

// libprotobuf's own messages, such as a string field in a submitted
// message that is not UTF-8. Its ERRORs concern input, not the daemon.
void log_protobuf(google::protobuf::LogLevel level, const char* file, int line, const std::string& message) {
  spdlog::level::level_enum ours = spdlog::level::debug;
  switch (level) {
    case google::protobuf::LOGLEVEL_INFO: ours = spdlog::level::debug; break;
    case google::protobuf::LOGLEVEL_WARNING:
    case google::protobuf::LOGLEVEL_ERROR: ours = spdlog::level::warn; break;
    case google::protobuf::LOGLEVEL_FATAL: ours = spdlog::level::critical; break;
  }
  spdlog::log(ours, "protobuf: {} ({}:{})", message, file, line);
}

}  // namespace

void configure_logging(v1::LogLevel level) {
  spdlog::drop("acommsd");  // configuring twice (tests) replaces the logger
  auto logger = spdlog::stderr_logger_mt("acommsd");
  // Under systemd the journal adds its own timestamps; elsewhere keep them.
  if (std::getenv("JOURNAL_STREAM") != nullptr) {
    logger->set_pattern("[%l] %v");
  } else {
    logger->set_pattern("%Y-%m-%dT%H:%M:%S.%e [%l] %v");
  }
  spdlog::set_default_logger(logger);
  switch (level) {
    case v1::TRACE: spdlog::set_level(spdlog::level::trace); break;
    case v1::DEBUG: spdlog::set_level(spdlog::level::debug); break;
    case v1::WARN: spdlog::set_level(spdlog::level::warn); break;
    case v1::ERROR: spdlog::set_level(spdlog::level::err); break;
    case v1::OFF: spdlog::set_level(spdlog::level::off); break;
    default: spdlog::set_level(spdlog::level::info); break;
  }
  spdlog::flush_on(spdlog::level::info);
  // Otherwise libprotobuf writes to stderr itself, in its own format and
  // past the configured level.
  google::protobuf::SetLogHandler(&log_protobuf);
}

}  // namespace acomms::core
