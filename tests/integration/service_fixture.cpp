#include "tests/integration/service_fixture.h"

#include "core/io/write_mesh.h"

namespace soiq::testing {

void ServiceTest::start(const std::vector<std::string>& args) {
  client_.reset();
  server_.reset();
  server_ = std::make_unique<SoiqdProcess>(db_path_, args);
  ASSERT_FALSE(server_->address().empty()) << "soiqd did not start:\n" << server_->log();
  if (args.empty()) client_ = std::make_unique<client::Client>(connect());
}

client::Client ServiceTest::connect(const std::string& token_file, const std::string& ca_file) const {
  client::ClientOptions o;
  o.address =
      (ca_file.empty() ? "" : "localhost:") + (ca_file.empty() ? server_->address() : std::to_string(server_->port()));
  o.token_file = token_file;
  o.tls_ca_file = ca_file;
  o.retry.attempts = 1;
  Result<client::Client> c = client::Client::connect(o);
  EXPECT_TRUE(c.ok()) << c.status().to_string();
  return std::move(c).value();
}

std::string ServiceTest::write_mesh_file(const TriangleMesh& mesh, const std::string& ext) {
  const std::string path = dir_.file("mesh" + std::to_string(++files_) + "." + ext);
  const Status s = write_mesh(mesh, path);
  EXPECT_TRUE(s.ok()) << s.to_string();
  return path;
}

v1::UploadSurfaceHeader surface_header(const std::string& patient, const std::string& study, const std::string& name,
                                       const std::string& laterality) {
  v1::UploadSurfaceHeader h;
  h.mutable_patient()->set_patient_id(patient);
  h.mutable_study()->set_study_uid(study);
  h.set_structure_name(name);
  h.set_laterality(laterality);
  return h;
}

Result<v1::UploadSurfaceResponse> ServiceTest::upload(const TriangleMesh& mesh, const std::string& patient,
                                                      const std::string& study, const std::string& name,
                                                      const std::string& laterality, const std::string& ext,
                                                      bool robust) {
  v1::UploadSurfaceHeader h = surface_header(patient, study, name, laterality);
  h.set_robust(robust);
  return client_->upload_surface(h, write_mesh_file(mesh, ext));
}

}  // namespace soiq::testing
