#include "webdriver.h"

#include <arpa/inet.h>
#include <google/protobuf/util/json_util.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <stdexcept>

#include "daemon_harness.h"

namespace acomms::testing {
namespace {

using namespace std::chrono_literals;

// One request on a fresh connection (chromedriver answers with
// Content-Length); the body of the response, or throws.
std::string http(int port, const std::string& method, const std::string& path, const std::string& body) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  timeval tv{30, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    throw std::runtime_error("chromedriver: cannot connect");
  }
  const std::string request = method + " " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" +
                              "Content-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
                              "\r\n\r\n" + body;
  ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  std::string response;
  char chunk[65536];
  while (true) {
    const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
    if (n <= 0) break;
    response.append(chunk, static_cast<std::size_t>(n));
    const std::size_t head = response.find("\r\n\r\n");
    if (head == std::string::npos) continue;
    // chromedriver writes "Content-Length:250", without the space.
    std::string lower = response.substr(0, head);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const std::size_t length_at = lower.find("content-length:");
    if (length_at != std::string::npos && response.size() >= head + 4 + std::stoul(lower.substr(length_at + 15))) {
      break;
    }
  }
  ::close(fd);
  const std::size_t head = response.find("\r\n\r\n");
  if (head == std::string::npos) throw std::runtime_error("chromedriver: no answer to " + method + " " + path);
  return response.substr(head + 4);
}

}  // namespace

std::optional<std::pair<std::string, std::string>> WebDriver::find_browser(std::string& why) {
  for (const char* chromium : {"/usr/bin/chromium", "/usr/lib/chromium/chromium"}) {
    if (::access(chromium, X_OK) != 0) continue;
    if (::access("/usr/bin/chromedriver", X_OK) != 0) {
      why = "chromedriver is not installed (apt-get install chromium-driver)";
      return std::nullopt;
    }
    return std::make_pair(std::string(chromium), std::string("/usr/bin/chromedriver"));
  }
  why = "chromium is not installed (packaging/install-deps.sh --test installs chromium and chromium-driver)";
  return std::nullopt;
}

WebDriver::WebDriver(const std::string& chromium, const std::string& chromedriver, const std::filesystem::path& dir)
    : profile_(dir / "chromium-profile") {
  std::filesystem::remove_all(profile_);
  std::filesystem::create_directories(profile_);
  port_ = free_tcp_port();
  driver_ = std::make_unique<ChildProcess>(
      chromedriver, std::vector<std::string>{"--port=" + std::to_string(port_), "--allowed-ips=127.0.0.1"},
      (dir / "chromedriver").string());
  const bool ready = wait_until(
      [&] {
        try {
          return http(port_, "GET", "/status", "").find("\"ready\":true") != std::string::npos;
        } catch (const std::exception&) {
          return false;
        }
      },
      15s, 100ms);
  if (!ready) throw std::runtime_error("chromedriver did not become ready: " + driver_->stderr_text());
  // Every host name but the loopback's fails to resolve: the page can only
  // work if everything it needs comes from the map server.
  const std::string args = "\"--headless\",\"--no-sandbox\",\"--disable-gpu\",\"--disable-quic\",\"--no-first-run\","
                           "\"--disable-background-networking\",\"--disable-component-update\",\"--disable-sync\","
                           "\"--disable-dev-shm-usage\",\"--window-size=1280,800\","
                           "\"--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1\","
                           "\"--user-data-dir=" + profile_.string() + "\"";
  const std::string body = "{\"capabilities\":{\"alwaysMatch\":{\"browserName\":\"chrome\",\"goog:chromeOptions\":{"
                           "\"binary\":\"" + chromium + "\",\"args\":[" + args + "]}}}}";
  google::protobuf::Value value = call("POST", "/session", body);
  session_ = value.struct_value().fields().at("sessionId").string_value();
  if (session_.empty()) throw std::runtime_error("chromedriver: no session");
}

WebDriver::~WebDriver() {
  try {
    if (!session_.empty()) call("DELETE", "/session/" + session_, "");
  } catch (const std::exception&) {
  }
  if (driver_ && driver_->running()) {
    driver_->signal(SIGTERM);
    driver_->wait(5s);
  }
  std::filesystem::remove_all(profile_);
}

google::protobuf::Value WebDriver::call(const std::string& method, const std::string& path, const std::string& body) {
  const std::string text = http(port_, method, path, body);
  google::protobuf::Struct reply;
  if (!google::protobuf::util::JsonStringToMessage(text, &reply).ok() || !reply.fields().count("value")) {
    throw std::runtime_error("chromedriver: " + method + " " + path + " answered: " + text.substr(0, 500));
  }
  const google::protobuf::Value& value = reply.fields().at("value");
  if (value.has_struct_value() && value.struct_value().fields().count("error")) {
    throw std::runtime_error("chromedriver: " + method + " " + path + ": " + text.substr(0, 1000));
  }
  return value;
}

void WebDriver::navigate(const std::string& url) {
  call("POST", "/session/" + session_ + "/url", "{\"url\":\"" + url + "\"}");
}

google::protobuf::Value WebDriver::execute(const std::string& script) {
  std::string escaped;
  for (char c : script) {
    if (c == '"' || c == '\\') escaped.push_back('\\');
    if (c == '\n') {
      escaped += "\\n";
      continue;
    }
    escaped.push_back(c);
  }
  return call("POST", "/session/" + session_ + "/execute/sync", "{\"script\":\"" + escaped + "\",\"args\":[]}");
}

std::string WebDriver::screenshot_png() {
  return base64_decode(call("GET", "/session/" + session_ + "/screenshot", "").string_value());
}

std::string base64_decode(const std::string& text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  int bits = 0, buffer = 0;
  for (char c : text) {
    const int v = value(c);
    if (v < 0) continue;  // '=' and line breaks
    buffer = (buffer << 6) | v;
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((buffer >> bits) & 0xff));
    }
  }
  return out;
}

}  // namespace acomms::testing
