#pragma once
// A gtest fixture with a real soiqd (on a free loopback port, its own SQLite file) and a
// soiq::client::Client connected to it, plus helpers to make and upload test meshes.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "client/soiq_client.h"
#include "core/base/triangle_mesh.h"
#include "tests/support/soiqd_process.h"

namespace soiq::testing {

class ServiceTest : public ::testing::Test {
 protected:
  void SetUp() override { start(); }

  // (Re)starts the server on the same database with `args`.
  void start(const std::vector<std::string>& args = {});
  client::Client connect(const std::string& token_file = "", const std::string& ca_file = "") const;

  // Writes `mesh` to a file of the given extension in the temp dir and uploads it.
  Result<v1::UploadSurfaceResponse> upload(const TriangleMesh& mesh, const std::string& patient,
                                           const std::string& study, const std::string& name,
                                           const std::string& laterality = "", const std::string& ext = "stl",
                                           bool robust = false);
  std::string write_mesh_file(const TriangleMesh& mesh, const std::string& ext);

  TempDir dir_;
  std::string db_path_ = dir_.file("soiq.db");
  std::unique_ptr<SoiqdProcess> server_;
  std::unique_ptr<client::Client> client_;
  int files_ = 0;
};

// A header for an upload with demographics that stage 1 can filter on.
v1::UploadSurfaceHeader surface_header(const std::string& patient, const std::string& study, const std::string& name,
                                       const std::string& laterality);

}  // namespace soiq::testing
