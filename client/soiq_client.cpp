#include "client/soiq_client.h"

#include <grpcpp/grpcpp.h>

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "client/cancel_watcher.h"
#include "client/grpc_status.h"
#include "client/read_token_file.h"
#include "client/server_target.h"
#include "grpc/health/v1/health.grpc.pb.h"

namespace soiq::client {

namespace v1 = soiq::v1;

namespace {

Result<std::string> read_pem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return not_found("cannot read TLS CA file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str().find("-----BEGIN CERTIFICATE-----") == std::string::npos) {
    return invalid_argument("TLS CA file '" + path + "' holds no PEM certificate");
  }
  return text.str();
}

}  // namespace

std::string format_from_path(const std::string& path) {
  std::string lower = path;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  auto ends = [&](const std::string& s) {
    return lower.size() > s.size() && lower.compare(lower.size() - s.size(), s.size(), s) == 0;
  };
  for (const char* f : {"nii.gz", "stl", "obj", "ply", "off", "vtk", "vtp", "nii", "nrrd", "mha"}) {
    if (ends(std::string(".") + f)) return f;
  }
  return "";
}

Result<Client> Client::connect(ClientOptions options) {
  if (options.address.empty()) {
    const char* env = std::getenv("SOIQ_SERVER");
    options.address = env && *env ? env : kDefaultAddress;
  }
  std::string token;
  if (!options.token_file.empty()) {
    SOIQ_ASSIGN_OR_RETURN(token, read_token_file(options.token_file));
  }
  SOIQ_ASSIGN_OR_RETURN(const ServerTarget target, server_target(options.address));
  options.address = target.shown;  // what messages name: "127.0.0.1:50051", never "127.0.0.1:0"
  std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
  if (!options.tls_ca_file.empty() || target.tls) {
    grpc::SslCredentialsOptions ssl;  // no roots given: gRPC's default roots (the system's)
    if (!options.tls_ca_file.empty()) {
      SOIQ_ASSIGN_OR_RETURN(ssl.pem_root_certs, read_pem(options.tls_ca_file));
    }
    credentials = grpc::SslCredentials(ssl);
  }
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(options.max_receive_message_bytes);
  args.SetMaxSendMessageSize(options.max_send_message_bytes);
  // Every address the name resolves to, in turn: "dns:///soiqd:50051" naming several soiqd
  // replicas (docker/compose.yaml's replicas profile) spreads calls over them; one address is
  // served as before.
  args.SetLoadBalancingPolicyName("round_robin");
  auto channel = grpc::CreateCustomChannel(target.grpc_target, credentials, args);
  return Client(std::move(options), std::move(token), std::move(channel));
}

Client::Client(ClientOptions options, std::string token, std::shared_ptr<grpc::Channel> channel)
    : options_(std::move(options)),
      token_(std::move(token)),
      channel_(std::move(channel)),
      stub_(v1::Soiq::NewStub(channel_)) {}

std::unique_ptr<grpc::ClientContext> Client::context(std::chrono::milliseconds deadline) const {
  auto ctx = std::make_unique<grpc::ClientContext>();
  ctx->set_deadline(std::chrono::system_clock::now() + deadline);
  if (!token_.empty()) ctx->AddMetadata("authorization", "Bearer " + token_);
  return ctx;
}

Status Client::map(const grpc::Status& status, std::chrono::milliseconds deadline,
                   const grpc::ClientContext& ctx) const {
  const bool answered = ctx.GetServerTrailingMetadata().count(kSoiqOriginKey) > 0;
  return from_grpc_status(status, options_.address, deadline, answered);
}

// `call(stub, context, response)` performs one attempt and returns gRPC's status.
// `long_running`: the stream deadline (calls that wait on a PACS or convert), else the unary one.
template <typename Response, typename Call>
Result<Response> Client::unary(Call call, bool retry, bool long_running) const {
  Response response;
  RetryPolicy policy = options_.retry;
  if (!retry) policy.attempts = 1;
  const std::chrono::milliseconds deadline = long_running ? options_.stream_deadline : options_.deadline;
  const Status s = with_retries(policy, [&]() -> Status {
    response.Clear();
    auto ctx = context(deadline);
    // Short calls too: one to a soiqd that hangs would otherwise hold Ctrl-C for its whole deadline.
    CancelWatcher watcher(cancel_flag(), ctx.get());
    return map(call(*stub_, ctx.get(), &response), deadline, *ctx);
  });
  if (!s.ok()) return s;
  return response;
}

Result<v1::ListPatientsResponse> Client::list_patients(const v1::ListPatientsRequest& request) const {
  return unary<v1::ListPatientsResponse>(
      [&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx, v1::ListPatientsResponse* out) {
        return stub.ListPatients(ctx, request, out);
      },
      true);
}

Result<v1::Patient> Client::get_patient(const std::string& patient_id) const {
  v1::GetPatientRequest request;
  request.set_patient_id(patient_id);
  return unary<v1::Patient>([&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx,
                                v1::Patient* out) { return stub.GetPatient(ctx, request, out); },
                            true);
}

Result<v1::ListStudiesResponse> Client::list_studies(const v1::ListStudiesRequest& request) const {
  return unary<v1::ListStudiesResponse>(
      [&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx, v1::ListStudiesResponse* out) {
        return stub.ListStudies(ctx, request, out);
      },
      true);
}

Result<v1::Study> Client::get_study(const std::string& study_uid) const {
  v1::GetStudyRequest request;
  request.set_study_uid(study_uid);
  return unary<v1::Study>(
      [&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx, v1::Study* out) { return stub.GetStudy(ctx, request, out); },
      true);
}

Result<v1::ListStructuresResponse> Client::list_structures(const v1::ListStructuresRequest& request) const {
  return unary<v1::ListStructuresResponse>(
      [&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx, v1::ListStructuresResponse* out) {
        return stub.ListStructures(ctx, request, out);
      },
      true);
}

Result<v1::Structure> Client::get_structure(int64_t id) const {
  v1::GetStructureRequest request;
  request.set_id(id);
  return unary<v1::Structure>([&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx,
                                  v1::Structure* out) { return stub.GetStructure(ctx, request, out); },
                              true);
}

Result<v1::DeleteResponse> Client::delete_structure(int64_t id) const {
  v1::DeleteStructureRequest request;
  request.set_id(id);
  return unary<v1::DeleteResponse>([&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx,
                                       v1::DeleteResponse* out) { return stub.DeleteStructure(ctx, request, out); },
                                   false);
}

Result<v1::DeleteResponse> Client::delete_patient(const std::string& patient_id) const {
  v1::DeletePatientRequest request;
  request.set_patient_id(patient_id);
  return unary<v1::DeleteResponse>([&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx,
                                       v1::DeleteResponse* out) { return stub.DeletePatient(ctx, request, out); },
                                   false);
}

Result<v1::PacsEchoResponse> Client::pacs_echo() const {
  const v1::PacsEchoRequest request;
  return unary<v1::PacsEchoResponse>([&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx,
                                         v1::PacsEchoResponse* out) { return stub.PacsEcho(ctx, request, out); },
                                     true, true);
}

Result<v1::PacsFindResponse> Client::pacs_find(const v1::PacsFindRequest& request) const {
  return unary<v1::PacsFindResponse>([&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx,
                                         v1::PacsFindResponse* out) { return stub.PacsFind(ctx, request, out); },
                                     true, true);
}

Result<v1::PacsPushResponse> Client::pacs_push(const v1::PacsPushRequest& request) const {
  // Retried: storing the same SEG again is harmless, but each attempt makes a new SOP instance, so
  // only UNAVAILABLE before the server answered is retried (with_retries' rule).
  return unary<v1::PacsPushResponse>([&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx,
                                         v1::PacsPushResponse* out) { return stub.PacsPush(ctx, request, out); },
                                     false, true);
}

Result<v1::ServerInfo> Client::server_info() const {
  const v1::GetServerInfoRequest request;
  return unary<v1::ServerInfo>([&](v1::Soiq::Stub& stub, grpc::ClientContext* ctx,
                                   v1::ServerInfo* out) { return stub.GetServerInfo(ctx, request, out); },
                               true);
}

Result<bool> Client::serving(const std::string& service) const {
  grpc::health::v1::HealthCheckRequest request;
  request.set_service(service);
  grpc::health::v1::HealthCheckResponse response;
  auto ctx = context(options_.deadline);
  CancelWatcher watcher(cancel_flag(), ctx.get());
  const Status s =
      map(grpc::health::v1::Health::NewStub(channel_)->Check(ctx.get(), request, &response), options_.deadline, *ctx);
  if (!s.ok()) return s;
  return response.status() == grpc::health::v1::HealthCheckResponse::SERVING;
}

Result<v1::FeaturesResponse> Client::compute_features(const v1::FeaturesRequest& request) const {
  // Features may convert the structure first: the longer deadline applies.
  v1::FeaturesResponse response;
  const Status s = with_retries(options_.retry, [&]() -> Status {
    response.Clear();
    auto ctx = context(options_.stream_deadline);
    CancelWatcher watcher(cancel_flag(), ctx.get());
    return map(stub_->ComputeFeatures(ctx.get(), request, &response), options_.stream_deadline, *ctx);
  });
  if (!s.ok()) return s;
  return response;
}

}  // namespace soiq::client
