#include "server/http/wado_images.h"

#include <charconv>

#include "dicom/dicom_json_metadata.h"
#include "dicom/instance_frames.h"
#include "dicom/instance_transcode.h"
#include "server/http/multipart.h"

namespace soiq::server::http {
namespace {

std::string instance_path(const std::string& base_url, const std::string& study_uid, const db::InstanceRecord& i) {
  return base_url + "/studies/" + study_uid + "/series/" + i.series_uid + "/instances/" + i.sop_instance_uid;
}

// An instance file read from the store with its bytes reserved in the budget first: the record
// says how large it is before a byte is read.
struct HeldFile {
  MemoryBudget::Reservation held;
  std::string bytes;
};

Result<HeldFile> read_kept_file(const AppEngines& e, const db::InstanceRecord& i, const HttpRequest& req) {
  HeldFile f;
  // Twice: the file as read, and once more when it is transcoded or its frames are cut out.
  SOIQ_ASSIGN_OR_RETURN(f.held, e.budget.reserve(2 * i.file_bytes, "sending instance " + i.sop_instance_uid,
                                                 stop_when_client_gone(req), "raise the budget"));
  SOIQ_ASSIGN_OR_RETURN(f.bytes, e.store.get_instance_file(i.file_sha256));
  return f;
}

// The file in the syntax asked, with its part's Content-Type.
Result<std::pair<std::string, std::string>> as_asked(std::string file, InstanceSyntax syntax) {
  if (syntax == InstanceSyntax::kExplicitLittleEndian) {
    SOIQ_ASSIGN_OR_RETURN(file, dicom::as_explicit_little_endian(std::move(file)));
    return std::make_pair(std::move(file),
                          std::string("application/dicom; transfer-syntax=") + dicom::kExplicitVrLittleEndianUid);
  }
  SOIQ_ASSIGN_OR_RETURN(const std::string uid, dicom::transfer_syntax_of(file));
  return std::make_pair(std::move(file), "application/dicom; transfer-syntax=" + uid);
}

// "1,3,5" -> {1, 3, 5}: frame numbers as PS3.18 8.3.3.3.1 lists them.
Result<std::vector<int64_t>> parse_frame_list(const std::string& text) {
  std::vector<int64_t> frames;
  size_t from = 0;
  while (from <= text.size()) {
    size_t comma = text.find(',', from);
    if (comma == std::string::npos) comma = text.size();
    int64_t n = 0;
    const char* first = text.data() + from;
    const char* last = text.data() + comma;
    const auto [end, ec] = std::from_chars(first, last, n);
    if (ec != std::errc() || end != last || n < 1)
      return invalid_argument("frame list '" + text + "': frames are numbers from 1, separated by commas");
    frames.push_back(n);
    if (frames.size() > 10000) return invalid_argument("frame list '" + text.substr(0, 64) + "...' is too long");
    from = comma + 1;
  }
  return frames;
}

// Frames go out uncompressed: the Accept header must admit application/octet-stream in Explicit
// VR Little Endian (PS3.18's default for it) or any syntax.
bool accepts_native_frames(const HttpRequest& req) {
  if (!req.has_header("Accept")) return true;
  for (const AcceptItem& a : accept_items(req)) {
    const std::string& syntax = a.transfer_syntax;
    const bool syntax_ok = syntax.empty() || syntax == "*" || syntax == dicom::kExplicitVrLittleEndianUid;
    if (a.media == "*/*" || a.media == "multipart/*") return true;
    if (is_multipart_related(a.media) && (a.type.empty() || a.type == "application/octet-stream") && syntax_ok)
      return true;
    if (a.media == "application/octet-stream" && syntax_ok) return true;
  }
  return false;
}

}  // namespace

Result<std::vector<db::InstanceRecord>> kept_series_instances(const AppEngines& e, const std::string& study_uid,
                                                              const std::string& series_uid,
                                                              const std::string& instance_uid) {
  Result<db::SeriesRecord> series = e.store.get_series(series_uid);
  if (!series.ok() && series.status().code() != StatusCode::kNotFound) return series.status();
  if (!series.ok() || series->study_uid != study_uid)
    return not_found("series '" + series_uid + "' not found in study '" + study_uid + "'");
  SOIQ_ASSIGN_OR_RETURN(std::vector<db::InstanceRecord> kept, e.store.list_instances(series_uid));
  if (kept.empty())
    return not_found("series " + series_uid +
                     " was stored without its DICOM instances (soiqd --keep-instances off, an image uploaded as a "
                     "file, or imported before soiq kept instances): import its files again to keep them, or "
                     "retrieve them from the PACS they came from");
  if (instance_uid.empty()) return kept;
  for (db::InstanceRecord& i : kept)
    if (i.sop_instance_uid == instance_uid) return std::vector<db::InstanceRecord>{std::move(i)};
  return not_found("instance '" + instance_uid + "' not found in series '" + series_uid + "'");
}

Result<std::vector<db::InstanceRecord>> kept_study_instances(const AppEngines& e, const std::string& study_uid) {
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, e.store.list_series(study_uid));
  std::vector<db::InstanceRecord> out;
  for (const db::SeriesRecord& s : series) {
    SOIQ_ASSIGN_OR_RETURN(std::vector<db::InstanceRecord> kept, e.store.list_instances(s.series_uid));
    for (db::InstanceRecord& i : kept) out.push_back(std::move(i));
  }
  return out;
}

std::string kept_instance_metadata(const HandlerContext& c, const std::string& study_uid,
                                   const db::InstanceRecord& instance) {
  return dicom::with_bulk_data_uri(instance.metadata, instance_path(c.base_url, study_uid, instance) + "/bulkdata");
}

InstanceSyntax instance_syntax(const HttpRequest& req) {
  if (!req.has_header("Accept")) return InstanceSyntax::kAsStored;
  bool explicit_le = false;
  for (const AcceptItem& a : accept_items(req)) {
    if (a.media == "*/*" || a.media == "multipart/*") return InstanceSyntax::kAsStored;
    if (!is_multipart_related(a.media) || !(a.type.empty() || a.type == "application/dicom")) continue;
    if (a.transfer_syntax == "*") return InstanceSyntax::kAsStored;
    // No transfer-syntax parameter means Explicit VR Little Endian (PS3.18 8.7.3.5.2).
    if (a.transfer_syntax.empty() || a.transfer_syntax == dicom::kExplicitVrLittleEndianUid) explicit_le = true;
  }
  return explicit_le ? InstanceSyntax::kExplicitLittleEndian : InstanceSyntax::kNotAcceptable;
}

Result<HttpReply> send_instances(const HandlerContext& c, const std::vector<db::InstanceRecord>& instances,
                                 std::vector<std::string> extra, InstanceSyntax syntax, const HttpRequest& req) {
  const std::string seg_type = std::string("application/dicom; transfer-syntax=") + dicom::kExplicitVrLittleEndianUid;
  const std::string boundary = random_boundary();
  const std::string content_type = "multipart/related; type=\"application/dicom\"; boundary=" + boundary;
  HttpReply whole;
  whole.content_type = content_type;
  // GET streams, one instance in memory at a time; HEAD is answered whole (its length is needed).
  const bool stream = bool(req.start_chunks);
  if (stream) SOIQ_RETURN_IF_ERROR(req.start_chunks(content_type));
  bool first = true;
  auto send = [&](std::string part, const std::string& type) -> Status {
    SOIQ_RETURN_IF_ERROR(check_part_against_boundary(boundary, part));
    std::string head = multipart_part_head(boundary, type, first);
    first = false;
    if (!stream) {
      whole.pieces.push_back(std::move(head));
      whole.pieces.push_back(std::move(part));
      return ok_status();
    }
    SOIQ_RETURN_IF_ERROR(req.send_chunk(std::move(head)));
    return req.send_chunk(std::move(part));
  };
  for (const db::InstanceRecord& i : instances) {
    SOIQ_ASSIGN_OR_RETURN(HeldFile file, read_kept_file(c.engines, i, req));
    SOIQ_ASSIGN_OR_RETURN(auto part, as_asked(std::move(file.bytes), syntax));
    SOIQ_RETURN_IF_ERROR(send(std::move(part.first), part.second));
    if (!stream) whole.held.push_back(std::move(file.held));
  }
  for (std::string& seg : extra) SOIQ_RETURN_IF_ERROR(send(std::move(seg), seg_type));
  std::string close = multipart_close(boundary, !first);
  if (!stream) {
    whole.pieces.push_back(std::move(close));
    return whole;
  }
  SOIQ_RETURN_IF_ERROR(req.send_chunk(std::move(close)));
  HttpReply done;
  done.chunked = true;
  return done;
}

Result<HttpReply> send_frames(const HandlerContext& c, const db::InstanceRecord& instance, const std::string& frames,
                              const HttpRequest& req) {
  if (!accepts_native_frames(req))
    return HttpReply{406,
                     std::string("multipart/related; type=\"application/octet-stream\"; transfer-syntax=") +
                         dicom::kExplicitVrLittleEndianUid,
                     "",
                     {}};
  std::vector<int64_t> numbers;
  if (!frames.empty()) {
    SOIQ_ASSIGN_OR_RETURN(numbers, parse_frame_list(frames));
  }
  SOIQ_ASSIGN_OR_RETURN(HeldFile file, read_kept_file(c.engines, instance, req));
  SOIQ_ASSIGN_OR_RETURN(std::vector<std::string> parts, dicom::instance_frames(file.bytes, numbers));
  file.bytes.clear();
  const std::string part_type =
      std::string("application/octet-stream; transfer-syntax=") + dicom::kExplicitVrLittleEndianUid;
  WrittenMultipart body = write_multipart_related(std::move(parts), part_type);
  HttpReply r;
  r.content_type = "multipart/related; type=\"application/octet-stream\"; boundary=" + body.boundary;
  r.pieces = std::move(body.pieces);
  r.held.push_back(std::move(file.held));
  return r;
}

}  // namespace soiq::server::http
