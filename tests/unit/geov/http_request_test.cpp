// The map server's request parser: what it accepts, and that each kind of
// bad request is refused with its status and a reason (never a crash).
#include <gtest/gtest.h>

#include "geov/http_request.h"

namespace acomms::cli::geov {
namespace {

HttpRefusal refusal_of(std::string_view head) {
  HttpParseResult result = parse_http_request(head);
  EXPECT_FALSE(result.request.has_value()) << head;
  return result.refusal;
}

TEST(HttpRequest, ParsesPathQueryAndHeaders) {
  HttpParseResult result =
      parse_http_request("GET /api/history?from=-10m&to=now&src=2&x=a%20b+c HTTP/1.1\r\nHost: ship:8080\r\nLast-Event-ID:  5:7 ");
  ASSERT_TRUE(result.request) << result.refusal.reason;
  const HttpRequest& r = *result.request;
  EXPECT_EQ(r.method, "GET");
  EXPECT_EQ(r.path, "/api/history");
  EXPECT_EQ(r.query.at("from"), "-10m");
  EXPECT_EQ(r.query.at("to"), "now");
  EXPECT_EQ(r.query.at("src"), "2");
  EXPECT_EQ(r.query.at("x"), "a b c");
  EXPECT_EQ(r.headers.at("host"), "ship:8080");
  EXPECT_EQ(r.headers.at("last-event-id"), "5:7");
}

TEST(HttpRequest, HeadIsAcceptedOtherMethodsAre405) {
  EXPECT_TRUE(parse_http_request("HEAD / HTTP/1.0").request);
  EXPECT_EQ(refusal_of("POST /api/fleet HTTP/1.1").status, 405);
  EXPECT_EQ(refusal_of("DELETE / HTTP/1.1").status, 405);
}

TEST(HttpRequest, AnOverlongHeadIs431) {
  const std::string head = "GET /" + std::string(kMaxHeadBytes, 'a') + " HTTP/1.1";
  HttpRefusal refusal = refusal_of(head);
  EXPECT_EQ(refusal.status, 431);
  EXPECT_NE(refusal.reason.find("8192"), std::string::npos);
}

TEST(HttpRequest, MalformedRequestLinesAre400Or505) {
  EXPECT_EQ(refusal_of("").status, 400);
  EXPECT_EQ(refusal_of("GET").status, 400);
  EXPECT_EQ(refusal_of("GET / HTTP/1.1 extra").status, 400);
  EXPECT_EQ(refusal_of("GET / SPDY/3").status, 505);
  EXPECT_EQ(refusal_of("GET relative HTTP/1.1").status, 400);
  EXPECT_EQ(refusal_of("GET http://elsewhere/ HTTP/1.1").status, 400);
  EXPECT_EQ(refusal_of(std::string("GET /a\x01 HTTP/1.1")).status, 400);
  EXPECT_EQ(refusal_of("GET /\xc3\xa9 HTTP/1.1").status, 400);
}

TEST(HttpRequest, BadQueriesAre400) {
  EXPECT_EQ(refusal_of("GET /?a=%zz HTTP/1.1").status, 400);
  EXPECT_EQ(refusal_of("GET /?a=%4 HTTP/1.1").status, 400);
  EXPECT_EQ(refusal_of("GET /?a=%00 HTTP/1.1").status, 400);  // a decoded control character
  std::string many = "GET /?";
  for (int i = 0; i <= static_cast<int>(kMaxQueryParams); ++i) many += "p" + std::to_string(i) + "=1&";
  HttpRefusal refusal = refusal_of(many + " HTTP/1.1");
  EXPECT_EQ(refusal.status, 400);
  EXPECT_NE(refusal.reason.find("query parameters"), std::string::npos);
}

TEST(HttpRequest, MalformedHeadersAre400AndABodyIs413) {
  EXPECT_EQ(refusal_of("GET / HTTP/1.1\r\nno colon here").status, 400);
  EXPECT_EQ(refusal_of("GET / HTTP/1.1\r\n: empty name").status, 400);
  EXPECT_EQ(refusal_of("GET / HTTP/1.1\r\nContent-Length: 10").status, 413);
  EXPECT_EQ(refusal_of("GET / HTTP/1.1\r\nTransfer-Encoding: chunked").status, 413);
  EXPECT_TRUE(parse_http_request("GET / HTTP/1.1\r\nContent-Length: 0").request);
}

TEST(HttpRequest, PercentDecodeRefusesTruncatedEscapes) {
  EXPECT_EQ(percent_decode("%41%42+c"), "AB c");
  EXPECT_FALSE(percent_decode("%"));
  EXPECT_FALSE(percent_decode("ab%4"));
  EXPECT_FALSE(percent_decode("%0a"));
}

}  // namespace
}  // namespace acomms::cli::geov
