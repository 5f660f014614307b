#include "client/soiq_client.h"

#include <gtest/gtest.h>

#include <atomic>

namespace soiq::client {
namespace {

ClientOptions unreachable() {
  ClientOptions o;
  o.address = "127.0.0.1:1";  // nothing listens on port 1
  o.retry.initial_backoff = std::chrono::milliseconds(1);
  o.deadline = o.stream_deadline = std::chrono::milliseconds(5000);
  return o;
}

TEST(Client, UnreachableServerIsUnavailableAndNamed) {
  const auto c = Client::connect(unreachable());
  ASSERT_TRUE(c.ok()) << c.status().to_string();
  const auto info = c->server_info();
  ASSERT_FALSE(info.ok());
  EXPECT_EQ(info.status().code(), StatusCode::kUnavailable);
  EXPECT_EQ(info.status().message().rfind("cannot reach soiqd at 127.0.0.1:1: ", 0), 0u) << info.status().message();
}

TEST(Client, QueryOnUnreachableServerIsUnavailableAndDeliversNothing) {
  const auto c = Client::connect(unreachable());
  ASSERT_TRUE(c.ok());
  int rows = 0;
  QueryHandlers h;
  h.on_row = [&](const soiq::v1::QueryRow&) { return ++rows, true; };
  const auto s = c->query(soiq::v1::QueryRequest(), h);
  EXPECT_EQ(s.status().code(), StatusCode::kUnavailable);
  EXPECT_EQ(rows, 0);
}

TEST(Client, AddressComesFromTheEnvironmentWhenNotGiven) {
  setenv("SOIQ_SERVER", "example.invalid:4242", 1);
  const auto c = Client::connect(ClientOptions{});
  unsetenv("SOIQ_SERVER");
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->address(), "example.invalid:4242");
  const auto d = Client::connect(ClientOptions{});
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d->address(), kDefaultAddress);
}

TEST(Client, UnreadableTokenFileFailsAtConnect) {
  ClientOptions o = unreachable();
  o.token_file = "/nonexistent/token";
  const auto c = Client::connect(o);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), StatusCode::kNotFound);
  EXPECT_NE(c.status().message().find("token file"), std::string::npos);
}

TEST(Client, CaFileWithoutCertificateIsRefused) {
  ClientOptions o = unreachable();
  o.tls_ca_file = "/dev/null";
  const auto c = Client::connect(o);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(c.status().message().find("PEM"), std::string::npos);
}

TEST(Client, UploadWithoutAKnownExtensionIsRefusedBeforeSending) {
  const auto c = Client::connect(unreachable());
  ASSERT_TRUE(c.ok());
  const auto r = c->upload_surface(soiq::v1::UploadSurfaceHeader(), "mesh.txt");
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
}

TEST(FormatFromPath, KnowsMeshAndImageExtensions) {
  EXPECT_EQ(format_from_path("a/b.STL"), "stl");
  EXPECT_EQ(format_from_path("ct.nii.gz"), "nii.gz");
  EXPECT_EQ(format_from_path("ct.nii"), "nii");
  EXPECT_EQ(format_from_path("x.vtp"), "vtp");
  EXPECT_EQ(format_from_path("x.txt"), "");
  EXPECT_EQ(format_from_path(".stl"), "");
}

}  // namespace
}  // namespace soiq::client
