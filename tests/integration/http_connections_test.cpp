// What HTTP connections cost soiqd over time: a slow client holds a connection, never a thread, so
// real clients are served while many dawdle; a head that stalls past --http-timeout is answered
// 408; connections past --http-max-connections get 503; a client that goes away stops its query;
// rows streamed as chunks end cleanly and leave the connection serving the next request.

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "tests/integration/cohort.h"
#include "tests/integration/raw_http.h"
#include "tests/integration/service_fixture.h"

namespace soiq::testing {
namespace {

class HttpConnectionsTest : public ServiceTest {
 protected:
  void SetUp() override {}

  void start_http(std::vector<std::string> args) {
    args.insert(args.begin(), {"--http", "127.0.0.1:0"});
    start(args);
    ASSERT_GT(server_->http_port(), 0) << server_->log();
  }

  int port() const { return server_->http_port(); }

  RawResponse get(const std::string& target) {
    RawConnection c(port());
    c.send("GET " + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
    return c.read_response();
  }

  // The log line of the first /soiq/v1/query answered, once soiqd has written it (60 s at most).
  std::string query_log_entry() {
    std::string log;
    for (int i = 0; i < 600 && log.find("path=/soiq/v1/query") == std::string::npos; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      log = server_->log();
    }
    const size_t line = log.find("path=/soiq/v1/query");
    return line == std::string::npos ? "" : log.substr(line, log.find('\n', line) - line);
  }
};

TEST_F(HttpConnectionsTest, SlowClientsHoldConnectionsNotThreads) {
  // 4 handler threads here (--workers 1): 32 half-sent heads would have held them all, 8 times.
  start_http({"--workers", "1"});
  std::vector<std::unique_ptr<RawConnection>> slow;
  for (int i = 0; i < 32; ++i) {
    slow.push_back(std::make_unique<RawConnection>(port()));
    ASSERT_TRUE(slow.back()->send("GET /dicom-web/studies HTTP/1.1\r\nHost: x\r\nX-Slow: "));
  }
  for (int i = 0; i < 8; ++i) EXPECT_EQ(get("/dicom-web/studies").status, 200);
  // The slow ones were held open meanwhile, and each is served once it finishes its head.
  for (auto& c : slow) {
    ASSERT_TRUE(c->send("1\r\n\r\n"));
    EXPECT_EQ(c->read_response().status, 200);
  }
}

TEST_F(HttpConnectionsTest, AHeadThatStallsIsAnswered408AndAnIdleConnectionClosed) {
  start_http({"--http-timeout", "1"});
  RawConnection stalled(port());
  ASSERT_TRUE(stalled.send("GET /dicom-web/studies HTTP/1.1\r\nHost: x\r\n"));
  const RawResponse r = stalled.read_response();
  EXPECT_EQ(r.status, 408) << r.head << r.body;
  EXPECT_NE(r.body.find("within 1 s (--http-timeout)"), std::string::npos) << r.body;
  EXPECT_TRUE(r.closed || stalled.closed_within(10));
  // A connection that never sends a byte is closed without an answer.
  RawConnection silent(port());
  EXPECT_TRUE(silent.closed_within(10));
  EXPECT_EQ(get("/dicom-web/studies").status, 200);
}

TEST_F(HttpConnectionsTest, ConnectionsPastTheCapAre503) {
  start_http({"--http-max-connections", "4"});
  std::vector<std::unique_ptr<RawConnection>> held;
  for (int i = 0; i < 4; ++i) {
    held.push_back(std::make_unique<RawConnection>(port()));
    ASSERT_TRUE(held.back()->send("GET /dicom-web/studies HTTP/1.1\r\nHost: x\r\n\r\n"));
    EXPECT_EQ(held.back()->read_response().status, 200);  // served, and kept alive
  }
  const RawResponse refused = get("/dicom-web/studies");
  EXPECT_EQ(refused.status, 503) << refused.head;
  EXPECT_NE(refused.body.find("--http-max-connections"), std::string::npos) << refused.body;
  held.clear();  // their connections close; the server counts them out
  RawResponse after;
  for (int attempt = 0; attempt < 100 && after.status != 200; ++attempt) {
    after = get("/dicom-web/studies");
    if (after.status != 200) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(after.status, 200);
}

TEST_F(HttpConnectionsTest, AClientThatGoesAwayStopsItsQuery) {
  start_http({"--workers", "1"});
  client_ = std::make_unique<client::Client>(connect());
  load_cohort(*this, *client_, dir_, 30);  // 120 structures, none computed yet
  {
    RawConnection c(port());
    ASSERT_TRUE(
        c.send("GET /soiq/v1/query?select=sphericity&select=mean%5Binside%2CMR%5D HTTP/1.1\r\nHost: x\r\n\r\n"));
    c.close();
  }
  // The query stops at its next look at the client (CANCELLED: 503, to nobody).
  const std::string entry = query_log_entry();
  ASSERT_FALSE(entry.empty()) << server_->log();
  EXPECT_NE(entry.find("status=503"), std::string::npos) << entry;
  // A client that stays is answered in full.
  const RawResponse whole = get("/soiq/v1/query?select=sphericity");
  EXPECT_EQ(whole.status, 200) << whole.body.substr(0, 300);
  EXPECT_NE(whole.body.find("\"rows\""), std::string::npos);
}

TEST_F(HttpConnectionsTest, RowsStreamAsChunksAndTheConnectionServesTheNextRequest) {
  start_http({"--workers", "2"});
  client_ = std::make_unique<client::Client>(connect());
  load_cohort(*this, *client_, dir_, 5);  // 20 structures
  RawConnection c(port());
  ASSERT_TRUE(
      c.send("GET /soiq/v1/query?select=sphericity HTTP/1.1\r\nHost: x\r\nAccept: application/x-ndjson\r\n\r\n"));
  const RawResponse streamed = c.read_response();
  ASSERT_EQ(streamed.status, 200) << streamed.head;
  EXPECT_EQ(streamed.header("Content-Type"), "application/x-ndjson");
  EXPECT_EQ(streamed.header("Content-Length"), "");
  // One chunk per line: the columns, a row per structure, the summary.
  ASSERT_EQ(streamed.chunks.size(), 22u) << streamed.body;
  EXPECT_EQ(streamed.chunks.front().rfind("{\"columns\":", 0), 0u) << streamed.chunks.front();
  for (size_t i = 1; i + 1 < streamed.chunks.size(); ++i)
    EXPECT_EQ(streamed.chunks[i].rfind("{\"row\":", 0), 0u) << streamed.chunks[i];
  EXPECT_EQ(streamed.chunks.back().rfind("{\"summary\":", 0), 0u) << streamed.chunks.back();
  EXPECT_FALSE(streamed.closed);
  // The same connection, the next request: the whole answer.
  ASSERT_TRUE(c.send("GET /soiq/v1/query?select=sphericity HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n"));
  const RawResponse whole = c.read_response();
  EXPECT_EQ(whole.status, 200) << whole.head;
  EXPECT_NE(whole.body.find("\"rows\""), std::string::npos);
  // HEAD of a streamed resource: the whole answer's head, no chunks.
  const RawResponse head = [&] {
    RawConnection h(port());
    h.send(
        "HEAD /soiq/v1/query?select=sphericity HTTP/1.1\r\nHost: x\r\nAccept: application/x-ndjson\r\nConnection: "
        "close\r\n\r\n");
    return h.read_response(10);
  }();
  EXPECT_EQ(head.status, 200) << head.head;
  EXPECT_EQ(head.header("Transfer-Encoding"), "");
}

TEST_F(HttpConnectionsTest, AClientGoneMidStreamIsCutShortAndSoiqdServesOn) {
  start_http({"--workers", "1"});
  client_ = std::make_unique<client::Client>(connect());
  load_cohort(*this, *client_, dir_, 30);  // 120 structures, none computed yet
  {
    RawConnection c(port());
    ASSERT_TRUE(
        c.send("GET /soiq/v1/query?select=sphericity&select=mean%5Binside%2CMR%5D HTTP/1.1\r\nHost: x\r\n"
               "Accept: application/x-ndjson\r\n\r\n"));
    // Gone once the answer has started: its columns have come, its rows are being computed.
    ASSERT_TRUE(c.received("{\"columns\":", 30));
    c.close();
  }
  const std::string entry = query_log_entry();
  ASSERT_FALSE(entry.empty()) << server_->log();
  EXPECT_EQ(entry.find("status=200"), std::string::npos) << "a query cut short is logged as such: " << entry;
  const RawResponse whole = get("/soiq/v1/query?select=sphericity");
  EXPECT_EQ(whole.status, 200) << whole.body.substr(0, 300);
}

}  // namespace
}  // namespace soiq::testing
