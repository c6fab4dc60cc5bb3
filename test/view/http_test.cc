// HTTP request parsing and path safety for vb_view.
#include "view/http.h"

#include <gtest/gtest.h>

namespace vb::view {
namespace {

TEST(HttpTest, ParsesRequestLineQueryAndHeaders) {
  HttpRequest r;
  std::string error;
  const std::string text =
      "GET /api/trial?result=trials%2Fenv042_p1.json&t=1.5&flag HTTP/1.1\r\n"
      "Host: 127.0.0.1:8765\r\nSec-WebSocket-Key:  abc== \r\n\r\n";
  ASSERT_EQ(ParseHttpRequest(text, &r, &error), HttpParse::kRequest) << error;
  EXPECT_EQ(r.method, "GET");
  EXPECT_EQ(r.path, "/api/trial");
  EXPECT_EQ(r.query.at("result"), "trials/env042_p1.json");
  EXPECT_EQ(r.query.at("t"), "1.5");
  EXPECT_EQ(r.query.at("flag"), "");
  EXPECT_EQ(r.headers.at("host"), "127.0.0.1:8765");
  EXPECT_EQ(r.headers.at("sec-websocket-key"), "abc==");
}

TEST(HttpTest, WaitsForTheWholeHead) {
  HttpRequest r;
  std::string error;
  EXPECT_EQ(ParseHttpRequest("GET / HTTP/1.1\r\nHost: x\r\n", &r, &error), HttpParse::kIncomplete);
  EXPECT_EQ(ParseHttpRequest("", &r, &error), HttpParse::kIncomplete);
}

TEST(HttpTest, RejectsMalformedRequests) {
  HttpRequest r;
  std::string error;
  EXPECT_EQ(ParseHttpRequest("GARBAGE\r\n\r\n", &r, &error), HttpParse::kBad);
  EXPECT_NE(error.find("request line"), std::string::npos);
  EXPECT_EQ(ParseHttpRequest("GET / SPDY/3\r\n\r\n", &r, &error), HttpParse::kBad);
  EXPECT_EQ(ParseHttpRequest("GET http://x/ HTTP/1.1\r\n\r\n", &r, &error), HttpParse::kBad);
  EXPECT_EQ(ParseHttpRequest("GET /a%zz HTTP/1.1\r\n\r\n", &r, &error), HttpParse::kBad);
  EXPECT_NE(error.find("percent"), std::string::npos);
  EXPECT_EQ(ParseHttpRequest("GET /a?x=%4 HTTP/1.1\r\n\r\n", &r, &error), HttpParse::kBad);
  EXPECT_EQ(ParseHttpRequest("GET / HTTP/1.1\r\nno colon here\r\n\r\n", &r, &error),
            HttpParse::kBad);
  EXPECT_NE(error.find("header"), std::string::npos);
  // A head that never ends is an error once it passes the limit, not a wait forever.
  EXPECT_EQ(ParseHttpRequest("GET / HTTP/1.1\r\nX: " + std::string(kMaxRequestHeadBytes, 'a'), &r,
                             &error),
            HttpParse::kBad);
}

TEST(HttpTest, SafeRelativePathStaysInsideItsRoot) {
  EXPECT_EQ(SafeRelativePath("/files/trials/a.json", "/files/"), "trials/a.json");
  EXPECT_EQ(SafeRelativePath("/files/../etc/passwd", "/files/"), "");
  EXPECT_EQ(SafeRelativePath("/files/a/../../b", "/files/"), "");
  EXPECT_EQ(SafeRelativePath("/files/./a", "/files/"), "");
  EXPECT_EQ(SafeRelativePath("/files//etc/passwd", "/files/"), "");
  EXPECT_EQ(SafeRelativePath("/files/", "/files/"), "");
  EXPECT_EQ(SafeRelativePath("/viewer/x", "/files/"), "");
  EXPECT_EQ(SafeRelativePath(std::string("/files/a\0b", 10), "/files/"), "");
  EXPECT_EQ(SafeRelativePath("/files/a\\..\\b", "/files/"), "");
  // Decoded before the check: %2e%2e arrives here as "..".
  std::string decoded;
  ASSERT_TRUE(UrlDecode("/files/%2e%2e/secret", false, &decoded));
  EXPECT_EQ(SafeRelativePath(decoded, "/files/"), "");
}

TEST(HttpTest, ResponsesCarryLengthAndType) {
  const std::string r = HttpResponse(200, ContentType("a.js"), "abc");
  EXPECT_EQ(r.rfind("HTTP/1.1 200 OK\r\n", 0), 0u);
  EXPECT_NE(r.find("Content-Type: text/javascript; charset=utf-8\r\n"), std::string::npos);
  EXPECT_NE(r.find("Content-Length: 3\r\n"), std::string::npos);
  EXPECT_EQ(r.substr(r.size() - 7), "\r\n\r\nabc");
  EXPECT_EQ(ContentType("x.PNG"), "image/png");
  EXPECT_EQ(ContentType("x.bin"), "application/octet-stream");
  const std::string e = HttpJsonError(422, "bad \"trial\"");
  EXPECT_NE(e.find("422 Unprocessable Entity"), std::string::npos);
  EXPECT_NE(e.find("{\"error\": \"bad \\\"trial\\\"\"}"), std::string::npos);
}

HttpRequest WithHeaders(const std::string& headers) {
  HttpRequest r;
  std::string error;
  EXPECT_EQ(ParseHttpRequest("GET / HTTP/1.1\r\n" + headers + "\r\n", &r, &error),
            HttpParse::kRequest)
      << error;
  return r;
}

TEST(HttpTest, OnlyTheServersOwnHostAndOriginAreAnswered) {
  for (const char* host : {"127.0.0.1:8765", "localhost:8765", "LOCALHOST:8765", "[::1]:8765"}) {
    EXPECT_EQ(HostOriginProblem(WithHeaders(std::string("Host: ") + host + "\r\n"), 8765), "")
        << host;
  }
  EXPECT_EQ(HostOriginProblem(WithHeaders("Host: 127.0.0.1:8765\r\nOrigin: http://localhost:8765\r\n"),
                              8765),
            "");
  EXPECT_EQ(HostOriginProblem(WithHeaders("Host: localhost\r\n"), 80), "");
  // NEW-10 of the probe at 8ff4def: any Host and any Origin were answered.
  for (const char* host : {"attacker.example", "attacker.example:8765", "127.0.0.1:8766",
                           "127.0.0.1", "127.0.0.2:8765", "localhost.attacker.example:8765",
                           "[::1]", "127.0.0.1:8765:1"}) {
    EXPECT_NE(HostOriginProblem(WithHeaders(std::string("Host: ") + host + "\r\n"), 8765), "")
        << host;
  }
  EXPECT_NE(HostOriginProblem(WithHeaders(""), 8765).find("no Host header"), std::string::npos);
  for (const char* origin : {"http://attacker.example", "http://127.0.0.1:9999", "null",
                             "https://127.0.0.1:8765", "http://127.0.0.1:8765.attacker.example"}) {
    const std::string problem = HostOriginProblem(
        WithHeaders(std::string("Host: 127.0.0.1:8765\r\nOrigin: ") + origin + "\r\n"), 8765);
    EXPECT_NE(problem.find("is not this server's page"), std::string::npos) << origin;
  }
}

}  // namespace
}  // namespace vb::view
