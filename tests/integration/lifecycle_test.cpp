// soiqd's life: persistence across a graceful restart and across a crash, many clients at once,
// TLS and bearer-token authentication.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "core/geometry/primitives.h"
#include "tests/integration/service_fixture.h"
#include "tests/support/child_process.h"

namespace soiq::testing {
namespace {

TEST_F(ServiceTest, WhatWasAcknowledgedSurvivesARestartAndACrash) {
  Result<v1::UploadSurfaceResponse> a = upload(uv_sphere({0, 0, 0}, 7, 12, 24), "P1", "S1", "a", "L");
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  EXPECT_EQ(server_->terminate(), 0) << "a graceful shutdown exits 0:\n" << server_->log();
  start();
  Result<v1::Structure> back = client_->get_structure(a->structure().id());
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  EXPECT_EQ(back->surface_sha256(), a->structure().surface_sha256());

  // Acknowledged, then killed without any chance to flush: still there.
  Result<v1::UploadSurfaceResponse> b = upload(uv_sphere({0, 0, 0}, 9, 12, 24), "P2", "S2", "b", "R");
  ASSERT_TRUE(b.ok());
  server_->kill_hard();
  start();
  Result<v1::Structure> b_back = client_->get_structure(b->structure().id());
  ASSERT_TRUE(b_back.ok()) << b_back.status().to_string();
  EXPECT_EQ(client_->server_info()->structures(), 2);
  // The features of a reopened store are computed, cached and read back like any others.
  v1::FeaturesRequest f;
  f.set_structure_id(b->structure().id());
  f.add_features("voxel_volume_mm3");
  ASSERT_TRUE(client_->compute_features(f).ok());
  EXPECT_TRUE(client_->compute_features(f)->from_cache());
}

TEST_F(ServiceTest, EightClientsUploadingAndQueryingAtOnceLoseNothing) {
  constexpr int kClients = 8, kEach = 5;
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (int c = 0; c < kClients; ++c) {
    threads.emplace_back([&, c] {
      client::Client mine = connect();
      for (int i = 0; i < kEach; ++i) {
        v1::UploadSurfaceHeader h = surface_header("P" + std::to_string(c), "S" + std::to_string(c),
                                                   "s" + std::to_string(i), i % 2 ? "L" : "R");
        const TriangleMesh m = uv_sphere({0, 0, 0}, 5 + c + 0.1 * i, 12, 24);
        Result<v1::UploadSurfaceResponse> r = mine.upload_surface(h, write_mesh_file(m, "stl"));
        if (!r.ok()) {
          ++failures;
          ADD_FAILURE() << r.status().to_string();
        }
        v1::QueryRequest q;
        q.mutable_stage1()->set_patient_id_glob("P" + std::to_string(c));
        v1::FeatureRef* sel = q.add_select();
        sel->set_name("voxel_volume_mm3");
        int64_t rows = 0;
        client::QueryHandlers handlers;
        handlers.on_row = [&](const v1::QueryRow&) {
          ++rows;
          return true;
        };
        Result<v1::QuerySummary> s = mine.query(q, handlers);
        if (!s.ok() || rows != i + 1) {
          ++failures;
          ADD_FAILURE() << "client " << c << " upload " << i << ": "
                        << (s.ok() ? "rows " + std::to_string(rows) : s.status().to_string());
        }
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(failures.load(), 0);
  Result<v1::ServerInfo> info = client_->server_info();
  ASSERT_TRUE(info.ok());
  EXPECT_EQ(info->structures(), kClients * kEach);
  EXPECT_EQ(info->patients(), kClients);
}

TEST_F(ServiceTest, ATokenIsRequiredWhenConfigured) {
  const std::string token = dir_.file("token");
  std::ofstream(token) << "s3cret-token-0123456789abcdef\n";
  const std::string wrong = dir_.file("wrong");
  std::ofstream(wrong) << "not-the-token-0123456789abcdef\n";
  start({"--token-file", token});
  client::Client anonymous = connect();
  Result<v1::ServerInfo> none = anonymous.server_info();
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code(), StatusCode::kUnauthenticated);
  EXPECT_NE(none.status().message().find("token"), std::string::npos);
  EXPECT_EQ(connect(wrong).server_info().status().code(), StatusCode::kUnauthenticated);
  client::Client good = connect(token);
  ASSERT_TRUE(good.server_info().ok()) << good.server_info().status().to_string();
  // Uploads are refused before anything is read or stored.
  Result<v1::UploadSurfaceResponse> r = anonymous.upload_surface(
      surface_header("P", "S", "x", ""), write_mesh_file(uv_sphere({0, 0, 0}, 5, 8, 16), "stl"));
  EXPECT_EQ(r.status().code(), StatusCode::kUnauthenticated);
  EXPECT_EQ(good.server_info()->structures(), 0);
}

TEST_F(ServiceTest, TlsWithAVerifiedCertificate) {
  const std::string key = dir_.file("key.pem"), cert = dir_.file("cert.pem");
  const std::string cmd = "openssl req -x509 -newkey rsa:2048 -nodes -keyout " + key + " -out " + cert +
                          " -days 1 -subj /CN=localhost -addext subjectAltName=DNS:localhost 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "openssl could not make a test certificate";
  start({"--tls-cert", cert, "--tls-key", key});
  client::Client tls = connect("", cert);
  Result<v1::ServerInfo> info = tls.server_info();
  ASSERT_TRUE(info.ok()) << info.status().to_string() << "\n" << server_->log();
  // A plaintext client cannot talk to a TLS server.
  Result<v1::ServerInfo> plain = connect().server_info();
  ASSERT_FALSE(plain.ok());
  EXPECT_EQ(plain.status().code(), StatusCode::kUnavailable);
}

TEST_F(ServiceTest, AServerThatIsDownIsUnavailable) {
  const std::string address = server_->address();
  ASSERT_EQ(server_->terminate(), 0);
  Result<v1::ServerInfo> r = client_->server_info();
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kUnavailable);
  EXPECT_NE(r.status().message().find(address), std::string::npos) << r.status().message();
}

TEST_F(ServiceTest, BadServerConfigurationIsRefusedAtStart) {
  SoiqdProcess bad_flag(db_path_, {"--workers", "zero"});
  EXPECT_FALSE(bad_flag.running());
  EXPECT_NE(bad_flag.log().find("--workers"), std::string::npos) << bad_flag.log();
  if (soiqd_on_postgres()) {
    // A database server nobody runs: refused at start, naming it.
    const std::string where = "127.0.0.1:" + std::to_string(free_loopback_port());
    SoiqdProcess bad_db(db_path_, {"--db", "postgresql://soiq@" + where + "/nowhere?connect_timeout=2"});
    EXPECT_FALSE(bad_db.running());
    EXPECT_NE(bad_db.log().find(where + "/nowhere"), std::string::npos) << bad_db.log();
  } else {
    const std::string not_db = dir_.file("not.db");
    std::ofstream(not_db) << "this is not a database, it is a text file of some length........\n";
    SoiqdProcess bad_db(not_db);
    EXPECT_FALSE(bad_db.running());
    EXPECT_NE(bad_db.log().find("not.db"), std::string::npos) << bad_db.log();
  }
  // A PACS address must be AE@HOST:PORT with a valid AE title and port, said at start, not at the first call.
  const std::vector<std::pair<std::string, std::string>> bad_pacs = {
      {"127.0.0.1:104", "has no AE title"},
      {"ORTHANC@127.0.0.1", "has no port"},
      {"ORTHANC@127.0.0.1:http", "not a number"},
      {"ORTHANC@127.0.0.1:70000", "outside 1..65535"},
      {"AN_AE_TITLE_OF_20_CH@127.0.0.1:104", "1 to 16 characters"},
  };
  for (const auto& [value, phrase] : bad_pacs) {
    SoiqdProcess bad_pacs_flag(db_path_, {"--pacs", value});
    EXPECT_FALSE(bad_pacs_flag.running()) << value;
    EXPECT_NE(bad_pacs_flag.log().find("--pacs"), std::string::npos) << bad_pacs_flag.log();
    EXPECT_NE(bad_pacs_flag.log().find(phrase), std::string::npos) << value << ": " << bad_pacs_flag.log();
  }
}

// gRPC would let a second server share the port (SO_REUSEPORT) and the calls would alternate between
// two stores; soiqd refuses at once instead, and the first one never notices.
TEST_F(ServiceTest, ASecondSoiqdOnATakenPortRefusesToStartAndTheFirstKeepsServing) {
  ASSERT_TRUE(upload(uv_sphere({0, 0, 0}, 10, 16, 32), "P1", "1.2.3", "ball").ok());
  const std::string address = "127.0.0.1:" + std::to_string(server_->port());
  SoiqdProcess second(dir_.file("second.db"), {"--listen", address});
  EXPECT_FALSE(second.running());
  EXPECT_NE(second.log().find(address + " is already in use: is another soiqd running?"), std::string::npos)
      << second.log();
  for (int i = 0; i < 8; ++i) {  // every call reaches the first server and its one structure
    Result<v1::ServerInfo> info = client_->server_info();
    ASSERT_TRUE(info.ok()) << info.status().to_string();
    EXPECT_EQ(info->structures(), 1);
  }
}

}  // namespace
}  // namespace soiq::testing

namespace soiq::testing {
namespace {

TEST_F(ServiceTest, TheStandardHealthServiceSaysServing) {
  Result<bool> serving = client_->serving();
  ASSERT_TRUE(serving.ok()) << serving.status().to_string();
  EXPECT_TRUE(*serving);
  // The health service answers without a token even when the API needs one (a load balancer's
  // probe has none).
  const std::string token = dir_.file("token");
  std::ofstream(token) << "s3cret-token-0123456789abcdef\n";
  start({"--token-file", token});
  Result<bool> anonymous = connect().serving();
  ASSERT_TRUE(anonymous.ok()) << anonymous.status().to_string();
  EXPECT_TRUE(*anonymous);
}

}  // namespace
}  // namespace soiq::testing
