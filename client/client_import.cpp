// Client::import_dicom: the client stream of ImportDicom, one file after another.
#include <grpcpp/grpcpp.h>

#include <fstream>

#include "client/cancel_watcher.h"
#include "client/dicom_files_to_send.h"
#include "client/soiq_client.h"

namespace soiq::client {

namespace v1 = soiq::v1;

Result<v1::ImportDicomResponse> Client::import_dicom(const std::vector<std::string>& paths, const ProgressFn& progress,
                                                     bool replace) const {
  SOIQ_ASSIGN_OR_RETURN(const std::vector<FileToSend> files, dicom_files_to_send(paths));
  int64_t total = 0;
  for (const FileToSend& f : files) total += f.size_bytes;
  v1::ImportDicomResponse response;
  auto ctx = context(options_.stream_deadline);
  CancelWatcher watcher(cancel_flag(), ctx.get());
  auto writer = stub_->ImportDicom(ctx.get(), &response);
  const size_t chunk = std::max<size_t>(1, options_.chunk_bytes);
  std::string buffer(chunk, '\0');
  int64_t sent = 0;
  bool open = true;
  if (replace) {
    v1::ImportDicomRequest options;
    options.mutable_options()->set_replace(true);
    open = writer->Write(options);
  }
  Status local = ok_status();
  for (const FileToSend& f : files) {
    std::ifstream in(f.local_path, std::ios::binary);
    if (!in) {
      local = not_found("cannot read '" + f.local_path + "'");
      break;
    }
    v1::ImportDicomRequest request;
    request.mutable_file()->set_path(f.sent_path);
    request.mutable_file()->set_size_bytes(f.size_bytes);
    open = writer->Write(request);
    // Reads exactly the announced size, so a file growing meanwhile cannot break the stream.
    for (int64_t left = f.size_bytes; open && left > 0;) {
      in.read(buffer.data(), std::streamsize(std::min<int64_t>(left, int64_t(chunk))));
      const std::streamsize got = in.gcount();
      if (got <= 0) {
        local = data_loss("'" + f.local_path + "' became shorter while it was being sent");
        break;
      }
      request.Clear();
      request.set_chunk(buffer.data(), size_t(got));
      open = writer->Write(request);
      left -= got;
      sent += got;
      if (open && progress) progress(sent, total);
    }
    if (!open || !local.ok()) break;
  }
  if (!local.ok()) {
    ctx->TryCancel();  // the server must not import a partial set
    writer->Finish();
    return local;
  }
  if (open) writer->WritesDone();
  // A closed stream means the server ended the call: Finish() says why.
  SOIQ_RETURN_IF_ERROR(map(writer->Finish(), options_.stream_deadline, *ctx));
  return response;
}

}  // namespace soiq::client
