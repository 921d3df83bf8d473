#pragma once
// A WebDriver client small enough for a test: starts Debian's chromedriver
// on a free port, opens a headless chromium session with the project's
// fixed flags (no sandbox, no GPU, no QUIC, no background network, a fresh
// profile, and no host name resolving but 127.0.0.1, so the page is shown
// working without any network), and speaks the W3C WebDriver protocol
// (JSON over HTTP on loopback) to navigate, run a script and take a
// screenshot.
//
// Thread-safety: one WebDriver per thread.

#include <google/protobuf/struct.pb.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "child_process.h"

namespace acomms::testing {

class WebDriver {
 public:
  // Paths of chromium and chromedriver, or nullopt with `why` when absent.
  static std::optional<std::pair<std::string, std::string>> find_browser(std::string& why);

  // Starts chromedriver and a session; throws std::runtime_error saying
  // what failed (with chromedriver's log).
  WebDriver(const std::string& chromium, const std::string& chromedriver, const std::filesystem::path& dir);
  ~WebDriver();

  void navigate(const std::string& url);
  // Runs `script` (a function body: "return ...") in the page; its JSON
  // result.
  google::protobuf::Value execute(const std::string& script);
  // The page as PNG bytes.
  std::string screenshot_png();

 private:
  // One HTTP request to chromedriver; the response's "value".
  google::protobuf::Value call(const std::string& method, const std::string& path, const std::string& body);

  int port_ = 0;
  std::unique_ptr<ChildProcess> driver_;
  std::string session_;
  std::filesystem::path profile_;
};

// Base64 as WebDriver's screenshots use it (RFC 4648, with padding).
std::string base64_decode(const std::string& text);

}  // namespace acomms::testing
