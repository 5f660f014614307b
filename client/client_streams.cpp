// The streaming calls of soiq::client::Client: uploads (client streaming), download, convert and
// query (server streaming). Unary calls are in soiq_client.cpp.
#include <grpcpp/grpcpp.h>

#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include "client/cancel_watcher.h"
#include "client/grpc_status.h"
#include "client/soiq_client.h"

namespace soiq::client {

namespace v1 = soiq::v1;

namespace {

// The file's bytes, read in pieces and never more than `max_bytes`: the path may be a pipe or
// /dev/stdin that never ends, which must fail at soiqd's limit rather than fill the memory.
Result<std::string> read_whole_file(const std::string& path, const char* what, int64_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return not_found(std::string("cannot read ") + what + " '" + path + "'");
  std::string bytes;
  std::string piece(size_t(1) << 20, '\0');
  while (in) {
    in.read(piece.data(), std::streamsize(piece.size()));
    bytes.append(piece.data(), size_t(in.gcount()));
    if (int64_t(bytes.size()) > max_bytes) {
      return resource_exhausted(std::string(what) + " '" + path + "' is larger than soiqd's upload limit of " +
                                std::to_string(max_bytes) + " bytes (soiqd --max-upload-bytes)");
    }
  }
  if (in.bad()) return data_loss(std::string("error reading ") + what + " '" + path + "'");
  return bytes;
}

Status cancelled_by_client(const char* what) {
  return Status(StatusCode::kCancelled, std::string(what) + " cancelled by the client");
}

// Reads a server stream to its end, handing each message to `deliver` (false: cancel the call).
// `delivered` tells whether anything reached the caller, which forbids a retry.
template <typename Message, typename Deliver>
grpc::Status drain(grpc::ClientReader<Message>& reader, grpc::ClientContext& ctx, Deliver deliver, bool& delivered,
                   bool& stopped) {
  Message message;
  while (reader.Read(&message)) {
    delivered = true;
    if (!deliver(message)) {
      stopped = true;
      ctx.TryCancel();
      break;
    }
  }
  return reader.Finish();
}

}  // namespace

template <typename Request, typename Response, typename Header>
Result<Response> Client::upload(const Header& header, std::string_view bytes, const ProgressFn& progress,
                                const char* what) const {
  if (header.format().empty()) {
    return invalid_argument(std::string(what) + " upload needs a format (e.g. stl, nii.gz)");
  }
  Response response;
  const size_t chunk = std::max<size_t>(1, options_.chunk_bytes);
  const Status s = with_retries(options_.retry, [&]() -> Status {
    response.Clear();
    auto ctx = context(options_.stream_deadline);
    CancelWatcher watcher(cancel_flag(), ctx.get());
    grpc::ClientContext* raw = ctx.get();
    auto writer = [&] {
      if constexpr (std::is_same_v<Request, v1::UploadSurfaceRequest>) {
        return stub_->UploadSurface(raw, &response);
      } else {
        return stub_->UploadImage(raw, &response);
      }
    }();
    Request request;
    *request.mutable_header() = header;
    bool open = writer->Write(request);
    for (size_t at = 0; open && at < bytes.size(); at += chunk) {
      request.Clear();
      request.set_chunk(std::string(bytes.substr(at, chunk)));
      open = writer->Write(request);
      if (open && progress) progress(int64_t(std::min(bytes.size(), at + chunk)), int64_t(bytes.size()));
    }
    if (open) writer->WritesDone();
    // A closed stream means the server ended the call: Finish() says why.
    return map(writer->Finish(), options_.stream_deadline, *ctx);
  });
  if (!s.ok()) return s;
  return response;
}

Result<v1::UploadSurfaceResponse> Client::upload_surface_bytes(const v1::UploadSurfaceHeader& header,
                                                               std::string_view bytes,
                                                               const ProgressFn& progress) const {
  return upload<v1::UploadSurfaceRequest, v1::UploadSurfaceResponse>(header, bytes, progress, "surface");
}

Result<v1::UploadSurfaceResponse> Client::upload_surface(v1::UploadSurfaceHeader header, const std::string& path,
                                                         const ProgressFn& progress) const {
  if (header.format().empty()) header.set_format(format_from_path(path));
  if (header.format().empty()) {
    return invalid_argument("'" + path + "' has no mesh extension; use .stl, .obj, .ply, .off, .vtk or .vtp");
  }
  SOIQ_ASSIGN_OR_RETURN(const v1::ServerInfo info, server_info());
  SOIQ_ASSIGN_OR_RETURN(const std::string bytes, read_whole_file(path, "surface model", info.max_upload_bytes()));
  return upload_surface_bytes(header, bytes, progress);
}

Result<v1::UploadImageResponse> Client::upload_image_bytes(const v1::UploadImageHeader& header, std::string_view bytes,
                                                           const ProgressFn& progress) const {
  return upload<v1::UploadImageRequest, v1::UploadImageResponse>(header, bytes, progress, "image");
}

Result<v1::UploadImageResponse> Client::upload_image(v1::UploadImageHeader header, const std::string& path,
                                                     const ProgressFn& progress) const {
  if (header.format().empty()) header.set_format(format_from_path(path));
  if (header.format().empty()) {
    return invalid_argument("'" + path + "' has no image extension; use .nii, .nii.gz, .nrrd or .mha");
  }
  SOIQ_ASSIGN_OR_RETURN(const v1::ServerInfo info, server_info());
  SOIQ_ASSIGN_OR_RETURN(const std::string bytes, read_whole_file(path, "image", info.max_upload_bytes()));
  return upload_image_bytes(header, bytes, progress);
}

template <typename Message>
Status Client::stream_to_file(
    const std::string& out_path,
    const std::function<std::unique_ptr<grpc::ClientReader<Message>>(grpc::ClientContext*)>& start,
    const std::function<const std::string*(const Message&)>& bytes_of, int64_t& written) const {
  bool delivered = false;
  Status local;  // a failure writing the file
  const Status s = with_retries(
      options_.retry,
      [&]() -> Status {
        written = 0;
        std::ofstream out(out_path, std::ios::binary | std::ios::trunc);
        if (!out) return not_found("cannot write '" + out_path + "'");
        auto ctx = context(options_.stream_deadline);
        CancelWatcher watcher(cancel_flag(), ctx.get());
        auto reader = start(ctx.get());
        bool stopped = false;
        const grpc::Status g = drain(
            *reader, *ctx,
            [&](const Message& m) {
              const std::string* data = bytes_of(m);
              if (data == nullptr) return true;
              out.write(data->data(), std::streamsize(data->size()));
              written += int64_t(data->size());
              if (!out) local = data_loss("error writing '" + out_path + "' (disk full?)");
              return bool(out);
            },
            delivered, stopped);
        if (!local.ok()) return local;
        return map(g, options_.stream_deadline, *ctx);
      },
      [&] { return !delivered; });
  if (!s.ok()) std::remove(out_path.c_str());
  return s;
}

Result<int64_t> Client::download_surface(v1::DownloadSurfaceRequest request, const std::string& out_path) const {
  if (request.format().empty()) request.set_format(format_from_path(out_path));
  if (request.format().empty() || request.format() == "nii" || request.format() == "nii.gz" ||
      request.format() == "nrrd" || request.format() == "mha") {
    return invalid_argument("output '" + out_path + "' needs a mesh extension: .stl, .obj, .ply, .vtk or .vtp");
  }
  int64_t written = 0;
  SOIQ_RETURN_IF_ERROR(stream_to_file<v1::DataChunk>(
      out_path, [&](grpc::ClientContext* ctx) { return stub_->DownloadSurface(ctx, request); },
      [](const v1::DataChunk& chunk) { return &chunk.data(); }, written));
  return written;
}

Result<v1::ConvertSummary> Client::convert(const v1::ConvertRequest& request, const ConvertHandlers& handlers) const {
  v1::ConvertSummary summary;
  bool delivered = false, stopped = false, fired = false;
  const Status s = with_retries(
      options_.retry,
      [&]() -> Status {
        auto ctx = context(options_.stream_deadline);
        CancelWatcher watcher(cancel_flag(handlers.cancel), ctx.get());
        auto reader = stub_->Convert(ctx.get(), request);
        const grpc::Status g = drain(
            *reader, *ctx,
            [&](const v1::ConvertResponse& r) {
              if (r.has_summary()) {
                summary = r.summary();
                return !handlers.on_summary || handlers.on_summary(r.summary());
              }
              if (r.has_runs()) return !handlers.on_runs || handlers.on_runs(r.runs());
              return !handlers.on_nifti || handlers.on_nifti(r.nifti_chunk());
            },
            delivered, stopped);
        fired = watcher.fired();
        return map(g, options_.stream_deadline, *ctx);
      },
      [&] { return !delivered; });
  if (stopped || fired) return cancelled_by_client("conversion");
  if (!s.ok()) return s;
  return summary;
}

Result<v1::QuerySummary> Client::query(const v1::QueryRequest& request, const QueryHandlers& handlers) const {
  std::optional<v1::QuerySummary> summary;
  bool row_seen = false, stopped = false, fired = false;
  const Status s = with_retries(
      options_.retry,
      [&]() -> Status {
        summary.reset();
        auto ctx = context(options_.stream_deadline);
        CancelWatcher watcher(cancel_flag(handlers.cancel), ctx.get());
        auto reader = stub_->Query(ctx.get(), request);
        bool any = false;  // progress events may repeat on a retry; rows may not
        const grpc::Status g = drain(
            *reader, *ctx,
            [&](const v1::QueryEvent& e) {
              if (e.has_row()) {
                row_seen = true;
                return !handlers.on_row || handlers.on_row(e.row());
              }
              if (e.has_progress()) return !handlers.on_progress || handlers.on_progress(e.progress());
              if (e.has_summary()) summary = e.summary();
              return true;
            },
            any, stopped);
        fired = watcher.fired();
        return map(g, options_.stream_deadline, *ctx);
      },
      [&] { return !row_seen && !stopped; });
  if (stopped || fired) return cancelled_by_client("query");
  if (!s.ok()) return s;
  if (!summary) return data_loss("soiqd at " + options_.address + " ended the query without its summary");
  return *summary;
}

Result<v1::SegInfo> Client::export_seg(const v1::ExportSegRequest& request, const std::string& out_path) const {
  std::optional<v1::SegInfo> info;
  int64_t written = 0;
  SOIQ_RETURN_IF_ERROR(stream_to_file<v1::ExportSegResponse>(
      out_path, [&](grpc::ClientContext* ctx) { return stub_->ExportSeg(ctx, request); },
      [&](const v1::ExportSegResponse& r) -> const std::string* {
        if (!r.has_info()) return &r.chunk();
        info = r.info();
        return nullptr;
      },
      written));
  Status check;
  if (!info) check = data_loss("soiqd at " + options_.address + " sent the SEG without its summary");
  if (check.ok() && written != info->size_bytes())
    check = data_loss("soiqd at " + options_.address + " announced a SEG of " + std::to_string(info->size_bytes()) +
                      " bytes but sent " + std::to_string(written));
  if (!check.ok()) {
    std::remove(out_path.c_str());
    return check;
  }
  return *info;
}

Result<v1::RtStructInfo> Client::export_rt_struct(const v1::ExportRtStructRequest& request,
                                                  const std::string& out_path) const {
  std::optional<v1::RtStructInfo> info;
  int64_t written = 0;
  SOIQ_RETURN_IF_ERROR(stream_to_file<v1::ExportRtStructResponse>(
      out_path, [&](grpc::ClientContext* ctx) { return stub_->ExportRtStruct(ctx, request); },
      [&](const v1::ExportRtStructResponse& r) -> const std::string* {
        if (!r.has_info()) return &r.chunk();
        info = r.info();
        return nullptr;
      },
      written));
  Status check;
  if (!info) check = data_loss("soiqd at " + options_.address + " sent the RT Structure Set without its summary");
  if (check.ok() && written != info->size_bytes())
    check = data_loss("soiqd at " + options_.address + " announced an RT Structure Set of " +
                      std::to_string(info->size_bytes()) + " bytes but sent " + std::to_string(written));
  if (!check.ok()) {
    std::remove(out_path.c_str());
    return check;
  }
  return *info;
}

Result<v1::RenderInfo> Client::render(const v1::RenderRequest& request, const std::string& out_path) const {
  std::optional<v1::RenderInfo> info;
  int64_t written = 0;
  SOIQ_RETURN_IF_ERROR(stream_to_file<v1::RenderResponse>(
      out_path, [&](grpc::ClientContext* ctx) { return stub_->Render(ctx, request); },
      [&](const v1::RenderResponse& r) -> const std::string* {
        if (!r.has_info()) return &r.chunk();
        info = r.info();
        return nullptr;
      },
      written));
  Status check;
  if (!info) check = data_loss("soiqd at " + options_.address + " sent the picture without its summary");
  if (check.ok() && written != info->size_bytes())
    check = data_loss("soiqd at " + options_.address + " announced a picture of " + std::to_string(info->size_bytes()) +
                      " bytes but sent " + std::to_string(written));
  if (!check.ok()) {
    std::remove(out_path.c_str());
    return check;
  }
  return *info;
}

Result<v1::ImportDicomResponse> Client::pacs_pull(const v1::PacsPullRequest& request,
                                                  const std::function<bool(const v1::PacsPullProgress&)>& on_progress,
                                                  const std::atomic<bool>* cancel) const {
  std::optional<v1::ImportDicomResponse> imported;
  auto ctx = context(options_.stream_deadline);
  CancelWatcher watcher(cancel_flag(cancel), ctx.get());
  auto reader = stub_->PacsPull(ctx.get(), request);
  bool delivered = false, stopped = false;
  const grpc::Status g = drain(
      *reader, *ctx,
      [&](const v1::PacsPullEvent& e) {
        if (e.has_imported()) imported = e.imported();
        if (e.has_progress()) return !on_progress || on_progress(e.progress());
        return true;
      },
      delivered, stopped);
  if (stopped || watcher.fired()) return cancelled_by_client("pull");
  SOIQ_RETURN_IF_ERROR(map(g, options_.stream_deadline, *ctx));
  if (!imported) return data_loss("soiqd at " + options_.address + " ended the pull without the import result");
  return *imported;
}

}  // namespace soiq::client
