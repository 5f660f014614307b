#pragma once
// soiq::client::Client: the C++ client of soiqd (proto/soiq/v1/soiq.proto). One method per RPC,
// each returning a soiq::Result with the API's messages as values; gRPC's status is mapped once
// (grpc_status.h), so callers see soiq's one error model and never a gRPC type.
//
// Connection: `address` (empty: $SOIQ_SERVER, else 127.0.0.1:50051) in any form server_target.h
// takes (HOST, HOST:PORT, http(s)://HOST:PORT, unix:PATH, ...); with `token_file`, every call
// carries "authorization: Bearer <token>"; with `tls_ca_file` (PEM) the channel is TLS and the
// server's certificate is verified against it; with an https:// address and no `tls_ca_file`,
// against the system's roots; otherwise plaintext. connect() reads the files and
// builds the channel; it does not wait for the server: an unreachable one shows as UNAVAILABLE on
// the first call ("cannot reach soiqd at ADDR: ...").
// Deadlines: `deadline` for unary calls, `stream_deadline` for uploads, downloads, convert and
// queries. Retries (retry.h) on UNAVAILABLE for the calls safe to repeat: gets, lists, info,
// features, uploads (the bytes are local and resent whole), and convert, download and query while
// nothing has been delivered to a callback yet. Deletes are not retried.
// Cancellation: a callback returning false, or a cancel flag becoming true (checked every 50 ms),
// cancels the call (ClientContext::TryCancel); the method then returns CANCELLED. The flag is the
// handlers' or pacs_pull's own, else ClientOptions::cancel, which covers every call. soiqd stores
// nothing of an upload or import whose stream was cancelled before it ended.
// Thread-safety: a Client may be used from several threads at once (gRPC stubs are thread-safe).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "client/retry.h"
#include "core/base/status.h"
#include "soiq/v1/soiq.grpc.pb.h"

namespace soiq::client {

inline constexpr const char* kDefaultAddress = "127.0.0.1:50051";

struct ClientOptions {
  std::string address;      // server_target.h forms; empty: $SOIQ_SERVER, else kDefaultAddress
  std::string token_file;   // bearer token; empty: none
  std::string tls_ca_file;  // PEM roots for TLS; empty: plaintext
  std::chrono::milliseconds deadline{30'000};
  std::chrono::milliseconds stream_deadline{600'000};
  int max_receive_message_bytes = 64 << 20;
  int max_send_message_bytes = 8 << 20;
  size_t chunk_bytes = 1 << 20;  // upload chunks; soiqd accepts 4 MiB messages by default
  RetryPolicy retry;
  const std::atomic<bool>* cancel = nullptr;  // true: cancel the call in progress (Ctrl-C)
};

// (bytes sent so far, total bytes); called after each chunk.
using ProgressFn = std::function<void(int64_t, int64_t)>;

struct ConvertHandlers {
  std::function<bool(const soiq::v1::ConvertSummary&)> on_summary;
  std::function<bool(std::string_view nifti_bytes)> on_nifti;
  std::function<bool(const soiq::v1::RunBatch&)> on_runs;
  const std::atomic<bool>* cancel = nullptr;
};

struct QueryHandlers {
  std::function<bool(const soiq::v1::QueryProgress&)> on_progress;
  std::function<bool(const soiq::v1::QueryRow&)> on_row;
  const std::atomic<bool>* cancel = nullptr;
};

class Client {
 public:
  // NOT_FOUND/INVALID_ARGUMENT for an unreadable token or CA file (read_token_file.h).
  static Result<Client> connect(ClientOptions options);

  const std::string& address() const { return options_.address; }
  const ClientOptions& options() const { return options_; }

  // Uploads: `header.format` may be empty when it follows from the path's extension (stl, obj, ply,
  // off, vtk, vtp; nii, nii.gz, nrrd, mha). The file is read whole, then sent in chunk_bytes chunks;
  // soiqd's upload limit is asked first and reading stops past it (RESOURCE_EXHAUSTED), so a pipe
  // that never ends is not buffered forever.
  Result<soiq::v1::UploadSurfaceResponse> upload_surface(soiq::v1::UploadSurfaceHeader header, const std::string& path,
                                                         const ProgressFn& progress = {}) const;
  Result<soiq::v1::UploadSurfaceResponse> upload_surface_bytes(const soiq::v1::UploadSurfaceHeader& header,
                                                               std::string_view bytes,
                                                               const ProgressFn& progress = {}) const;
  Result<soiq::v1::UploadImageResponse> upload_image(soiq::v1::UploadImageHeader header, const std::string& path,
                                                     const ProgressFn& progress = {}) const;
  Result<soiq::v1::UploadImageResponse> upload_image_bytes(const soiq::v1::UploadImageHeader& header,
                                                           std::string_view bytes,
                                                           const ProgressFn& progress = {}) const;

  // Imports DICOM files and folders (walked recursively, client/dicom_files_to_send.h) through the
  // server's ImportDicom; progress counts bytes. Not retried: an import the server committed
  // before the connection failed would be stored twice. `replace`: content stored under the same
  // UIDs is replaced (else ALREADY_EXISTS when it differs; soiq.proto ImportOptions).
  Result<soiq::v1::ImportDicomResponse> import_dicom(const std::vector<std::string>& paths,
                                                     const ProgressFn& progress = {}, bool replace = false) const;

  Result<soiq::v1::ListPatientsResponse> list_patients(const soiq::v1::ListPatientsRequest& request) const;
  Result<soiq::v1::Patient> get_patient(const std::string& patient_id) const;
  Result<soiq::v1::ListStudiesResponse> list_studies(const soiq::v1::ListStudiesRequest& request) const;
  Result<soiq::v1::Study> get_study(const std::string& study_uid) const;
  Result<soiq::v1::ListStructuresResponse> list_structures(const soiq::v1::ListStructuresRequest& request) const;
  Result<soiq::v1::Structure> get_structure(int64_t id) const;
  Result<soiq::v1::DeleteResponse> delete_structure(int64_t id) const;
  Result<soiq::v1::DeleteResponse> delete_patient(const std::string& patient_id) const;
  Result<soiq::v1::ServerInfo> server_info() const;
  // The standard health service (grpc.health.v1.Health/Check) for `service` ("" = the server as a
  // whole): true when SERVING, false when NOT_SERVING (e.g. shutting down). Not retried.
  Result<bool> serving(const std::string& service = "") const;
  Result<soiq::v1::FeaturesResponse> compute_features(const soiq::v1::FeaturesRequest& request) const;

  // The stored surface, written to `out_path` (replaced; removed again on failure). Returns the
  // bytes written. `request.format` empty: from out_path's extension.
  Result<int64_t> download_surface(soiq::v1::DownloadSurfaceRequest request, const std::string& out_path) const;

  // Streams the conversion to the handlers; returns the summary (the first message).
  Result<soiq::v1::ConvertSummary> convert(const soiq::v1::ConvertRequest& request,
                                           const ConvertHandlers& handlers) const;

  // Streams progress and rows to the handlers; returns the closing summary.
  Result<soiq::v1::QuerySummary> query(const soiq::v1::QueryRequest& request, const QueryHandlers& handlers) const;

  // A picture of a structure written to `out_path` (replaced; removed again on failure).
  Result<soiq::v1::RenderInfo> render(const soiq::v1::RenderRequest& request, const std::string& out_path) const;

  // DICOM out and the PACS soiqd is configured with (its --pacs). Long calls: stream_deadline.
  // The SEG of imported structures written to `out_path` (replaced; removed again on failure).
  Result<soiq::v1::SegInfo> export_seg(const soiq::v1::ExportSegRequest& request, const std::string& out_path) const;
  // The RT Structure Set of imported structures, written the same way.
  Result<soiq::v1::RtStructInfo> export_rt_struct(const soiq::v1::ExportRtStructRequest& request,
                                                  const std::string& out_path) const;
  Result<soiq::v1::PacsEchoResponse> pacs_echo() const;
  Result<soiq::v1::PacsFindResponse> pacs_find(const soiq::v1::PacsFindRequest& request) const;
  // Pulls studies into soiq; `on_progress` after each instance (false cancels: nothing is stored).
  // Not retried: the server may have stored the import before the connection failed.
  Result<soiq::v1::ImportDicomResponse> pacs_pull(
      const soiq::v1::PacsPullRequest& request,
      const std::function<bool(const soiq::v1::PacsPullProgress&)>& on_progress = {},
      const std::atomic<bool>* cancel = nullptr) const;
  // Not retried: every attempt would store a new SEG instance on the PACS.
  Result<soiq::v1::PacsPushResponse> pacs_push(const soiq::v1::PacsPushRequest& request) const;

 private:
  Client(ClientOptions options, std::string token, std::shared_ptr<grpc::Channel> channel);
  // A fresh context per attempt: deadline and authorization.
  std::unique_ptr<grpc::ClientContext> context(std::chrono::milliseconds deadline) const;
  // `ctx` tells whether soiqd itself answered (its "soiq-origin" trailer) or the transport failed.
  Status map(const grpc::Status& status, std::chrono::milliseconds deadline, const grpc::ClientContext& ctx) const;
  template <typename Response, typename Call>
  Result<Response> unary(Call call, bool retry, bool long_running = false) const;
  // A server stream written to `out_path` (replaced; removed on failure), retried while nothing
  // was received. `bytes_of` gives a message's file bytes, or nullptr for one it took otherwise.
  template <typename Message>
  Status stream_to_file(const std::string& out_path,
                        const std::function<std::unique_ptr<grpc::ClientReader<Message>>(grpc::ClientContext*)>& start,
                        const std::function<const std::string*(const Message&)>& bytes_of, int64_t& written) const;
  template <typename Request, typename Response, typename Header>
  Result<Response> upload(const Header& header, std::string_view bytes, const ProgressFn& progress,
                          const char* what) const;

  // `own` when set, else options_.cancel.
  const std::atomic<bool>* cancel_flag(const std::atomic<bool>* own = nullptr) const {
    return own != nullptr ? own : options_.cancel;
  }

  ClientOptions options_;
  std::string token_;
  std::shared_ptr<grpc::Channel> channel_;
  std::shared_ptr<soiq::v1::Soiq::Stub> stub_;
};

// The format of a mesh or image file from its extension: "stl", "nii.gz", ...; "" when unknown.
std::string format_from_path(const std::string& path);

}  // namespace soiq::client
