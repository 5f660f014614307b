#include "client/server_target.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace soiq::client {
namespace {

TEST(ServerTarget, EveryAcceptedFormGivesTheTargetGrpcDials) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"127.0.0.1", "127.0.0.1:50051"},
      {"127.0.0.1:7000", "127.0.0.1:7000"},
      {"db1.example.org", "db1.example.org:50051"},
      {"[::1]", "[::1]:50051"},
      {"[::1]:7000", "[::1]:7000"},
      {"::1", "[::1]:50051"},
      {"http://127.0.0.1:50051", "127.0.0.1:50051"},
      {"http://127.0.0.1:50051/", "127.0.0.1:50051"},
      {"http://db1", "db1:50051"},
      {"https://db1:443", "db1:443"},
      {"unix:/run/soiq/soiqd.sock", "unix:/run/soiq/soiqd.sock"},
      {"unix:///run/soiq/soiqd.sock", "unix:///run/soiq/soiqd.sock"},
      {"dns:///db1:7000", "dns:///db1:7000"},
      {"dns:///db1", "dns:///db1:50051"},
      {"dns:db1", "dns:db1:50051"},
      {"ipv4:127.0.0.1:7000,127.0.0.2:7000", "ipv4:127.0.0.1:7000,127.0.0.2:7000"},
  };
  for (const auto& [written, target] : cases) {
    const Result<ServerTarget> t = server_target(written);
    ASSERT_TRUE(t.ok()) << written << ": " << t.status().to_string();
    EXPECT_EQ(t->grpc_target, target) << written;
  }
}

TEST(ServerTarget, OnlyHttpsAsksForTls) {
  EXPECT_TRUE(server_target("https://db1")->tls);
  EXPECT_FALSE(server_target("http://db1")->tls);
  EXPECT_FALSE(server_target("db1:7000")->tls);
}

TEST(ServerTarget, BadAddressesAreInvalidArgumentNamingTheTextAndTheForms) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "is empty"},
      {"grpc://db1:7000", "scheme 'grpc://'"},
      {"http://db1:7000/soiq", "has a path"},
      {"db1:http", "port 'http'"},
      {"db1:0", "port '0'"},
      {"db1:70000", "port '70000'"},
      {":7000", "has no host"},
      {"[::1", "unclosed '['"},
      {"db1 :7000", "spaces"},
  };
  for (const auto& [written, phrase] : cases) {
    const Result<ServerTarget> t = server_target(written);
    ASSERT_FALSE(t.ok()) << written;
    EXPECT_EQ(t.status().code(), StatusCode::kInvalidArgument) << written;
    EXPECT_NE(t.status().message().find(phrase), std::string::npos) << written << ": " << t.status().message();
    EXPECT_NE(t.status().message().find("HOST:PORT"), std::string::npos) << t.status().message();
  }
}

}  // namespace
}  // namespace soiq::client
