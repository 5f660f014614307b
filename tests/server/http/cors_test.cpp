// CORS for the one configured origin (server/http/cors.h): its preflight is answered, its answers
// carry the headers; another origin, a request without Origin, and no configured origin get none.
#include "server/http/cors.h"

#include <gtest/gtest.h>

namespace soiq::server::http {
namespace {

HttpRequest request(const std::string& method, std::vector<std::pair<std::string, std::string>> headers) {
  HttpRequest r;
  r.method = method;
  for (auto& [name, value] : headers) r.headers.emplace_back(name, value);
  return r;
}

std::string header(const std::multimap<std::string, std::string>& h, const std::string& name) {
  const auto it = h.find(name);
  return it == h.end() ? "" : it->second;
}

TEST(Cors, TheAllowedOriginsPreflightIsAnsweredWithTheMethodsAndHeaders) {
  const std::string origin = "http://127.0.0.1:3000";
  const auto preflight =
      cors_preflight(origin, request("OPTIONS", {{"Origin", origin}, {"Access-Control-Request-Method", "GET"}}));
  ASSERT_TRUE(preflight.has_value());
  EXPECT_EQ(preflight->status, 204);
  EXPECT_EQ(header(preflight->headers, "Access-Control-Allow-Origin"), origin);
  EXPECT_NE(header(preflight->headers, "Access-Control-Allow-Headers").find("Authorization"), std::string::npos);
  EXPECT_NE(header(preflight->headers, "Access-Control-Allow-Methods").find("GET"), std::string::npos);
  EXPECT_EQ(header(preflight->headers, "Vary"), "Origin");
  // The connection adds every answer's CORS headers: a preflight's must still name its origin once.
  std::multimap<std::string, std::string> written = preflight->headers;
  add_cors_headers(origin, request("OPTIONS", {{"Origin", origin}, {"Access-Control-Request-Method", "GET"}}), written);
  EXPECT_EQ(written.count("Access-Control-Allow-Origin"), 1u);
  EXPECT_EQ(written.count("Vary"), 1u);
}

TEST(Cors, AnotherOriginNoOriginAndNoConfigurationGetNothing) {
  const std::string origin = "http://127.0.0.1:3000";
  const auto ask = [](const std::string& from) {
    return request("OPTIONS", {{"Origin", from}, {"Access-Control-Request-Method", "GET"}});
  };
  EXPECT_FALSE(cors_preflight(origin, ask("http://127.0.0.1:3001")).has_value());
  EXPECT_FALSE(cors_preflight("", ask(origin)).has_value());
  EXPECT_FALSE(cors_preflight(origin, request("OPTIONS", {{"Origin", origin}})).has_value());  // not a preflight
  EXPECT_FALSE(cors_preflight(origin, request("GET", {{"Origin", origin}})).has_value());
  std::multimap<std::string, std::string> h;
  add_cors_headers(origin, request("GET", {{"Origin", "http://evil.example"}}), h);
  add_cors_headers(origin, request("GET", {}), h);
  add_cors_headers("", request("GET", {{"Origin", origin}}), h);
  EXPECT_TRUE(h.empty());
}

TEST(Cors, AnswersToTheAllowedOriginCarryItAndAnyOriginIsNamedStar) {
  std::multimap<std::string, std::string> h;
  add_cors_headers("http://a:1", request("GET", {{"Origin", "http://a:1"}}), h);
  EXPECT_EQ(header(h, "Access-Control-Allow-Origin"), "http://a:1");
  EXPECT_NE(header(h, "Access-Control-Expose-Headers").find("Content-Type"), std::string::npos);
  std::multimap<std::string, std::string> any;
  add_cors_headers("*", request("GET", {{"Origin", "http://b:2"}}), any);
  EXPECT_EQ(header(any, "Access-Control-Allow-Origin"), "*");
}

}  // namespace
}  // namespace soiq::server::http
