// soiqd's HTTP side holds its bounds against clients that do not play by the rules, before the
// token is checked: floods of headers, overlong lines, bodies where none belongs or past the limit
// (chunked or not), lying lengths, thousands of byte ranges. Each gets its own status and a JSON
// error naming the limit, soiqd's memory stays where it was, and a real client is served after.
// The raw bytes go through RawConnection: no HTTP library would send them.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "tests/integration/raw_http.h"
#include "tests/integration/service_fixture.h"
#include "tests/support/address_sanitizer.h"

namespace soiq::testing {
namespace {

using nlohmann::json;

constexpr char kToken[] = "limits-test-token-0123456789";

class HttpLimitsTest : public ServiceTest {
 protected:
  void SetUp() override {
    token_file_ = dir_.file("token");
    { std::ofstream(token_file_) << kToken << "\n"; }
    start({"--http", "127.0.0.1:0", "--token-file", token_file_, "--memory-budget", "256M", "--max-upload-bytes",
           "100000"});
    ASSERT_GT(server_->http_port(), 0) << server_->log();
  }

  int port() const { return server_->http_port(); }

  // The error a refusal carries: {"error": {"status": N, "message": ...}}.
  static json error_of(const RawResponse& r) {
    const json j = json::parse(r.body, nullptr, false);
    return j.is_object() && j.contains("error") ? j["error"] : json();
  }

  // A request a real client sends, with the token: answered 200.
  void expect_served() {
    RawConnection c(port());
    ASSERT_TRUE(c.send(std::string("GET /dicom-web/studies HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer ") + kToken +
                       "\r\n\r\n"));
    const RawResponse r = c.read_response();
    EXPECT_EQ(r.status, 200) << r.head << r.body;
  }

  void expect_refusal(const RawResponse& r, int status, const std::string& words) {
    EXPECT_EQ(r.status, status) << r.head;
    const json e = error_of(r);
    ASSERT_TRUE(e.is_object()) << "no JSON error body: " << r.body.substr(0, 200);
    EXPECT_EQ(e["status"], status);
    EXPECT_NE(e["message"].get<std::string>().find(words), std::string::npos) << e["message"];
    EXPECT_EQ(r.header("Content-Type"), "application/json");
  }

  std::string token_file_;
};

TEST_F(HttpLimitsTest, HeadFloodsAreRefusedWhileReadingAndCostAlmostNothing) {
  const long long before = server_->peak_rss_bytes();
  ASSERT_GT(before, 0);
  {
    // Two hundred short headers: counted (an Apache-like 100 at most).
    std::string head = "GET /dicom-web/studies HTTP/1.1\r\nHost: x\r\n";
    for (int i = 0; i < 200; ++i) head += "X-Flood-" + std::to_string(i) + ": v\r\n";
    RawConnection c(port());
    ASSERT_TRUE(c.send(head + "\r\n"));
    expect_refusal(c.read_response(), 431, "more than 100 header lines");
  }
  {
    // One header line of 10 KB.
    RawConnection c(port());
    ASSERT_TRUE(c.send("GET /dicom-web/studies HTTP/1.1\r\nX-Long: " + std::string(10000, 'a') + "\r\n\r\n"));
    expect_refusal(c.read_response(), 431, "the header 'X-Long' is longer than the 8192 bytes");
  }
  {
    // A request line of 20 KB, whole.
    RawConnection c(port());
    ASSERT_TRUE(c.send("GET /dicom-web/studies?x=" + std::string(20000, 'q') + " HTTP/1.1\r\n\r\n"));
    expect_refusal(c.read_response(), 414, "request line is longer than the 8192 bytes");
  }
  // Heads that never end, from 64 clients at once, up to 4 MiB each: refused at 64 KiB of each.
  std::vector<std::thread> floods;
  std::vector<RawResponse> answers(64);
  std::atomic<size_t> sent{0};
  for (int i = 0; i < 64; ++i) {
    floods.emplace_back([&, i] {
      RawConnection c(port());
      if (i % 2 == 0) {
        c.send("GET /dicom-web/studies HTTP/1.1\r\n");
        sent += c.flood("X-Endless: 0123456789abcdef0123456789abcdef\r\n", size_t(4) << 20);
      } else {
        c.send("GET /");
        sent += c.flood(std::string(4096, 'a'), size_t(4) << 20);
      }
      answers[size_t(i)] = c.read_response();
    });
  }
  for (std::thread& t : floods) t.join();
  for (int i = 0; i < 64; ++i) {
    if (i % 2 == 0) {
      expect_refusal(answers[size_t(i)], 431, "headers are longer than the 65536 bytes");
    } else {
      expect_refusal(answers[size_t(i)], 414, "request line is longer than the 8192 bytes");
    }
  }
  const long long after = server_->peak_rss_bytes();
  // soiqd held at most 64 KiB of each connection's head.
  EXPECT_LT(after - before, 32ll << 20) << "VmHWM grew from " << before << " to " << after;
  std::printf("head floods: %zu bytes sent by 64 clients; soiqd's VmHWM %lld -> %lld bytes\n", sent.load(), before,
              after);
  expect_served();
}

TEST_F(HttpLimitsTest, BodiesAreBoundedOnEveryRouteChunkedOrNot) {
  const std::string auth = std::string("Authorization: Bearer ") + kToken + "\r\n";
  const long long before = server_->peak_rss_bytes();
  ASSERT_GT(before, 0);
  {
    // A chunked body to a route that takes none: refused at its head.
    RawConnection c(port());
    ASSERT_TRUE(c.send("GET /dicom-web/studies HTTP/1.1\r\n" + auth + "Transfer-Encoding: chunked\r\n\r\n"));
    c.flood("10000\r\n" + std::string(0x10000, 'z') + "\r\n", size_t(64) << 20);
    expect_refusal(c.read_response(), 413, "GET /dicom-web/studies takes no request body");
  }
  {
    // The same before the token: refused all the same, nothing read.
    RawConnection c(port());
    ASSERT_TRUE(c.send("POST /soiq/v1/query HTTP/1.1\r\nContent-Length: 5000000000\r\n\r\n"));
    const RawResponse r = c.read_response();
    EXPECT_EQ(r.status, 401) << r.head;
    EXPECT_EQ(r.header("Connection"), "close");
  }
  {
    // A chunked STOW past --max-upload-bytes (100000): refused as the chunks pass it.
    RawConnection c(port());
    ASSERT_TRUE(c.send("POST /dicom-web/studies HTTP/1.1\r\n" + auth +
                       "Content-Type: multipart/related; type=\"application/dicom\"; boundary=b\r\n"
                       "Transfer-Encoding: chunked\r\n\r\n"));
    c.flood("4000\r\n" + std::string(0x4000, 'z') + "\r\n", size_t(64) << 20);
    expect_refusal(c.read_response(), 413, "--max-upload-bytes, 100000 bytes");
  }
  {
    // A chunk that announces more than is left is refused before it is read.
    RawConnection c(port());
    ASSERT_TRUE(c.send("POST /dicom-web/studies HTTP/1.1\r\n" + auth +
                       "Content-Type: multipart/related; type=\"application/dicom\"; boundary=b\r\n"
                       "Transfer-Encoding: chunked\r\n\r\nffffffffff\r\n"));
    expect_refusal(c.read_response(), 413, "--max-upload-bytes");
  }
  {
    // A Content-Length past the limit, with Expect: 100-continue: refused before any byte goes.
    RawConnection c(port());
    ASSERT_TRUE(c.send("POST /dicom-web/studies HTTP/1.1\r\n" + auth +
                       "Content-Type: multipart/related; type=\"application/dicom\"; boundary=b\r\n"
                       "Content-Length: 200000\r\nExpect: 100-continue\r\n\r\n"));
    expect_refusal(c.read_response(), 413, "--max-upload-bytes");
  }
  {
    // A negative or malformed Content-Length is not HTTP: 400 at once, no thread waits for it.
    RawConnection c(port());
    ASSERT_TRUE(c.send("POST /dicom-web/studies HTTP/1.1\r\n" + auth + "Content-Length: -5\r\n\r\n"));
    expect_refusal(c.read_response(5), 400, "not valid HTTP/1.1");
  }
  {
    // Expect: 100-continue within the limit: "100 Continue", then the body is read and answered.
    RawConnection c(port());
    const std::string body = "--b\r\nContent-Type: application/dicom\r\n\r\nnot DICOM\r\n--b--\r\n";
    ASSERT_TRUE(c.send("POST /dicom-web/studies HTTP/1.1\r\n" + auth +
                       "Content-Type: multipart/related; type=\"application/dicom\"; boundary=b\r\n"
                       "Content-Length: " +
                       std::to_string(body.size()) + "\r\nExpect: 100-continue\r\n\r\n"));
    const RawResponse go_on = c.read_response();
    EXPECT_EQ(go_on.status, 100) << go_on.head;
    ASSERT_TRUE(c.send(body));
    const RawResponse r = c.read_response();
    EXPECT_EQ(r.status, 409) << r.head << r.body;  // read, and not a DICOM file
    EXPECT_NE(r.body.find("00081198"), std::string::npos) << r.body;
  }
  // 128 MiB of chunks offered above: soiqd kept none of it in memory (a STOW body spools to disk).
  const long long after = server_->peak_rss_bytes();
  // (Under ASan freed buffers sit in its quarantine: the bound is the release build's.)
  if (!SOIQ_TEST_UNDER_ASAN) {
    EXPECT_LT(after - before, 32ll << 20) << "VmHWM grew from " << before << " to " << after;
  }
  std::printf("body floods: soiqd's VmHWM %lld -> %lld bytes\n", before, after);
  expect_served();
}

TEST_F(HttpLimitsTest, OneByteRangeIsServedAndManyAreRefused) {
  const std::string get = std::string("GET /dicom-web/studies HTTP/1.1\r\nAuthorization: Bearer ") + kToken + "\r\n";
  RawConnection c(port());
  ASSERT_TRUE(c.send(get + "\r\n"));
  const RawResponse whole = c.read_response();
  ASSERT_EQ(whole.status, 200);
  EXPECT_EQ(whole.header("Accept-Ranges"), "bytes");
  ASSERT_TRUE(c.send(get + "Range: bytes=0-0\r\n\r\n"));
  const RawResponse one = c.read_response();
  EXPECT_EQ(one.status, 206) << one.head;
  EXPECT_EQ(one.body, whole.body.substr(0, 1));
  EXPECT_EQ(one.header("Content-Range"), "bytes 0-0/" + std::to_string(whole.body.size()));
  // Thousands of ranges: one copy of the answer each, were they served. Refused, on a kept-alive
  // connection that goes on serving.
  std::string ranges = "bytes=0-0";
  for (int i = 0; i < 5000; ++i) ranges += ",0-0";
  const long long before = server_->peak_rss_bytes();
  ASSERT_GT(before, 0);
  for (int i = 0; i < 500; ++i) {  // 500 times over, ~1750 ranges each
    ASSERT_TRUE(c.send(get + "Range: " + ranges.substr(0, 7000) + "\r\n\r\n"));
    const RawResponse many = c.read_response();
    if (i == 0) expect_refusal(many, 416, "at most 1 byte range");
    ASSERT_EQ(many.status, 416) << many.head;
  }
  const long long after = server_->peak_rss_bytes();
  if (!SOIQ_TEST_UNDER_ASAN) {
    EXPECT_LT(after - before, 32ll << 20) << "VmHWM grew from " << before << " to " << after;
  }
  std::printf("range floods: soiqd's VmHWM %lld -> %lld bytes\n", before, after);
  ASSERT_TRUE(c.send(get + "Range: bytes=100000-\r\n\r\n"));
  const RawResponse past = c.read_response();
  expect_refusal(past, 416, "past the end");
  EXPECT_EQ(past.header("Content-Range"), "bytes */" + std::to_string(whole.body.size()));
  // A Range that does not parse is ignored: the whole answer.
  ASSERT_TRUE(c.send(get + "Range: lines=1-2\r\n\r\n"));
  EXPECT_EQ(c.read_response().status, 200);
}

TEST_F(HttpLimitsTest, MalformedRequestsGetTheirOwnStatus) {
  struct Case {
    std::string bytes;
    int status;
    std::string words;
  };
  const std::vector<Case> cases = {
      {"GARBAGE\r\n\r\n", 400, "not valid HTTP/1.1"},
      {"GET /dicom-web/studies HTTP/2.0\r\n\r\n", 505, "HTTP/1.0 and 1.1"},
      {"GET /dicom-web/studies%zz HTTP/1.1\r\n\r\n", 400, "malformed percent escape"},
      {"GET /dicom-web/studies%00 HTTP/1.1\r\n\r\n", 400, "encoded NUL"},
      {"GET http://elsewhere/ HTTP/1.1\r\n\r\n", 400, "starting with '/'"},
      {"GET /dicom-web/studies HTTP/1.1\r\nBad Header: x\r\n\r\n", 400, "not valid HTTP/1.1"},
  };
  for (const Case& k : cases) {
    RawConnection c(port());
    ASSERT_TRUE(c.send(k.bytes));
    SCOPED_TRACE(k.bytes);
    expect_refusal(c.read_response(), k.status, k.words);
  }
  expect_served();
}

}  // namespace
}  // namespace soiq::testing
