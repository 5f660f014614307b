#include "client/grpc_status.h"

#include <grpcpp/support/status.h>
#include <gtest/gtest.h>

namespace soiq::client {
namespace {

using std::chrono::milliseconds;

TEST(FromGrpcStatus, KeepsTheCodeNumberAndTheServersMessage) {
  const Status s =
      from_grpc_status(grpc::Status(grpc::StatusCode::FAILED_PRECONDITION, "mesh 'a' has 12 boundary edges"), "host:1",
                       milliseconds(1000));
  EXPECT_EQ(s.code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ(s.message(), "mesh 'a' has 12 boundary edges");
}

TEST(FromGrpcStatus, OkIsOk) { EXPECT_TRUE(from_grpc_status(grpc::Status::OK, "h:1", milliseconds(1)).ok()); }

TEST(FromGrpcStatus, EveryCodeKeepsItsNumber) {
  for (int code = 1; code <= 16; ++code) {
    const Status s = from_grpc_status(grpc::Status(grpc::StatusCode(code), "m"), "h:1", milliseconds(1));
    EXPECT_EQ(int(s.code()), code);
  }
}

TEST(FromGrpcStatus, UnavailableNamesTheAddress) {
  const Status s = from_grpc_status(grpc::Status(grpc::StatusCode::UNAVAILABLE, "Connection refused"),
                                    "127.0.0.1:50051", milliseconds(1000));
  EXPECT_EQ(s.code(), StatusCode::kUnavailable);
  EXPECT_EQ(s.message(), "cannot reach soiqd at 127.0.0.1:50051: Connection refused");
}

// soiqd answered UNAVAILABLE itself (its PACS is down): the PACS is named, soiqd is not blamed.
TEST(FromGrpcStatus, UnavailableFromSoiqdItselfKeepsItsMessage) {
  const Status s = from_grpc_status(
      grpc::Status(grpc::StatusCode::UNAVAILABLE, "C-ECHO with PACS 'X' at 127.0.0.1:4242 failed: connection refused"),
      "127.0.0.1:50051", milliseconds(1000), /*answered_by_soiqd=*/true);
  EXPECT_EQ(s.code(), StatusCode::kUnavailable);
  EXPECT_EQ(s.message(), "C-ECHO with PACS 'X' at 127.0.0.1:4242 failed: connection refused");
}

TEST(FromGrpcStatus, ClientDeadlineSaysWhatToDo) {
  const Status s = from_grpc_status(grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED, "Deadline Exceeded"), "h:1",
                                    milliseconds(2500));
  EXPECT_EQ(s.code(), StatusCode::kDeadlineExceeded);
  EXPECT_NE(s.message().find("within the deadline (2.5 s)"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("--timeout"), std::string::npos) << s.message();
}

TEST(FromGrpcStatus, ServerDeadlineMessageIsKept) {
  const Status s =
      from_grpc_status(grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED, "query stopped after 120 of 400 structures"),
                       "h:1", milliseconds(1000));
  EXPECT_EQ(s.message(), "query stopped after 120 of 400 structures");
}

}  // namespace
}  // namespace soiq::client
