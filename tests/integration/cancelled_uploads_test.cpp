// Uploads and imports whose client stream is cancelled (Ctrl-C, a lost connection) store nothing,
// even when every byte of a valid file had arrived: a stream's end and its cancellation look the
// same to the server's Read(), and what arrived may be a file cut where it still parses.
// Each test sends a whole valid file, waits until soiqd has surely read it, then cancels instead of
// ending the stream, and checks that no record appeared (the same file sent and ended is stored).

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "core/geometry/primitives.h"
#include "tests/integration/service_fixture.h"
#include "tests/support/test_data.h"

namespace soiq::testing {
namespace {

class CancelledUploads : public ServiceTest {
 protected:
  std::unique_ptr<v1::Soiq::Stub> stub() const {
    return v1::Soiq::NewStub(grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  }

  // Writes `messages` on the stream, then ends it (`cancel` false) or, after soiqd has had time to
  // read them all, cancels it. Returns the call's gRPC status.
  template <typename Request, typename Start>
  grpc::StatusCode send(const std::vector<Request>& messages, bool cancel, Start start) {
    grpc::ClientContext ctx;
    auto writer = start(&ctx);
    for (const Request& m : messages) EXPECT_TRUE(writer->Write(m));
    if (cancel) {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      ctx.TryCancel();
    } else {
      writer->WritesDone();
    }
    return writer->Finish().error_code();
  }

  v1::ServerInfo info() const {
    Result<v1::ServerInfo> i = client_->server_info();
    EXPECT_TRUE(i.ok()) << i.status().to_string();
    return i.ok() ? *i : v1::ServerInfo();
  }
};

TEST_F(CancelledUploads, ASurfaceWhoseStreamWasCancelledIsNotStored) {
  std::vector<v1::UploadSurfaceRequest> messages(2);
  *messages[0].mutable_header() = surface_header("P1", "1.2.3", "sphere", "");
  messages[0].mutable_header()->set_format("obj");
  messages[1].set_chunk(file_bytes(write_mesh_file(uv_sphere({0, 0, 0}, 10, 12, 24), "obj")));
  auto s = stub();
  v1::UploadSurfaceResponse response;
  const auto start = [&](grpc::ClientContext* ctx) { return s->UploadSurface(ctx, &response); };

  EXPECT_EQ(send(messages, /*cancel=*/true, start), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(info().structures(), 0);
  EXPECT_EQ(info().patients(), 0);

  EXPECT_EQ(send(messages, /*cancel=*/false, start), grpc::StatusCode::OK);  // the same bytes are a whole file
  EXPECT_EQ(info().structures(), 1);
}

TEST_F(CancelledUploads, ADicomImportWhoseStreamWasCancelledImportsNothing) {
  const std::string ct = file_bytes(std::string(SOIQ_TEST_DATA_DIR) + "/dicom/CT_small.dcm");
  ASSERT_FALSE(ct.empty());
  std::vector<v1::ImportDicomRequest> messages(2);
  messages[0].mutable_file()->set_path("CT_small.dcm");
  messages[0].mutable_file()->set_size_bytes(int64_t(ct.size()));
  messages[1].set_chunk(ct);
  auto s = stub();
  v1::ImportDicomResponse response;
  const auto start = [&](grpc::ClientContext* ctx) { return s->ImportDicom(ctx, &response); };

  EXPECT_EQ(send(messages, /*cancel=*/true, start), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(info().studies(), 0);
  EXPECT_EQ(info().series(), 0);

  EXPECT_EQ(send(messages, /*cancel=*/false, start), grpc::StatusCode::OK);
  EXPECT_EQ(info().studies(), 1);
}

}  // namespace
}  // namespace soiq::testing
