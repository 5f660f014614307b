// STOW-RS (PS3.18 10.5): a multipart/related body of DICOM files imported exactly as ImportDicom
// (`soiq import`) imports the same files (server/app/dicom_import.h, one transaction), then each
// instance's outcome in the PS3.18 response: ReferencedSOPSequence for those stored, with a
// WarningReason where part of one was skipped, FailedSOPSequence with a FailureReason for the
// others. The problems' words go in Warning headers (DICOM's response has codes only).
//
// The body reaches a temporary file as it arrives (http_connection.cpp) and is read here through a
// read-only mapping, so a request of --max-upload-bytes costs disk and page cache, not soiqd's
// memory (as gRPC's import).
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "dicom/scan_dicom.h"
#include "server/app/dicom_import.h"
#include "server/http/http_handlers.h"
#include "server/http/http_status.h"
#include "server/http/multipart.h"
#include "server/util/temp_dir.h"

namespace soiq::server::http {
namespace {

using nlohmann::json;

constexpr size_t kMaxParts = 100000;
constexpr int kMaxWarningHeaders = 20;

// PS3.4 Annex GG / PS3.18 Table 10.5.3-2 reasons.
constexpr int kProcessingFailure = 0x0110;
constexpr int kDuplicateSopInstance = 0x0111;  // stored under this UID with other content
constexpr int kSopClassNotSupported = 0x0122;
constexpr int kOutOfResources = 0xA700;
constexpr int kStudyMismatch = 0xA900;  // "data set does not match": not of the study the URL names
constexpr int kCannotUnderstand = 0xC000;
constexpr int kElementsDiscarded = 0xB006;

struct Part {
  std::string file;  // relative name in the folder
  std::string sop_class, sop_instance, series, study, modality;
  bool read = false;
  int failure = 0;
  int warning = 0;
};

json ui(const std::string& v) { return {{"vr", "UI"}, {"Value", {v}}}; }

json reference(const Part& p, int reason_tag_code, const char* reason_tag) {
  json item = {{"00081150", ui(p.sop_class)}, {"00081155", ui(p.sop_instance)}};
  if (reason_tag_code != 0) item[reason_tag] = {{"vr", "US"}, {"Value", {reason_tag_code}}};
  return item;
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\r' || c == '\n' || c == '"') c = ' ';
  return s;
}

// Each part's outcome from what the import stored and the problems it reported.
void judge(std::vector<Part>& parts, const DicomImportResult& r) {
  std::map<std::string, const ImportProblem*> by_path;
  for (const ImportProblem& p : r.problems) by_path.emplace(p.path, &p);
  std::map<std::string, bool> stored_series;
  for (const db::SeriesRecord& s : r.series) stored_series[s.series_uid] = true;
  for (Part& p : parts) {
    if (p.failure != 0) continue;
    if (!p.read) {
      p.failure = kCannotUnderstand;
      continue;
    }
    const bool structures = p.modality == "RTSTRUCT" || p.sop_class == "1.2.840.10008.5.1.4.1.1.66.4";
    bool contributed = false;
    for (const ImportedStructure& s : r.structures)
      contributed = contributed || s.structure.source_uid.rfind(p.sop_instance + "/", 0) == 0;
    const bool file_problem = by_path.count(p.file) > 0;
    if (by_path.count(p.series) > 0) {
      p.failure = kProcessingFailure;
    } else if (stored_series.count(p.series) > 0) {
      // a slice of a stored image series
    } else if (structures) {
      // A structure set or SEG stored nothing only when a problem says why; one recognised (soiq's
      // own SEG back) has none and is stored already.
      if (file_problem) {
        if (contributed) {
          p.warning = kElementsDiscarded;
        } else {
          p.failure = kProcessingFailure;
        }
      }
    } else {
      p.failure = kSopClassNotSupported;
    }
  }
}

// A file mapped read-only, unmapped and closed on destruction.
class MappedFile {
 public:
  static Result<MappedFile> open(const std::string& path) {
    MappedFile m;
    m.fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    struct stat st {};
    if (m.fd_ < 0 || ::fstat(m.fd_, &st) != 0) return internal_error("cannot read back the received body");
    m.size_ = size_t(st.st_size);
    if (m.size_ > 0) {
      m.data_ = ::mmap(nullptr, m.size_, PROT_READ, MAP_PRIVATE, m.fd_, 0);
      if (m.data_ == MAP_FAILED) return internal_error("cannot map the received body");
    }
    return m;
  }
  MappedFile() = default;
  MappedFile(MappedFile&& o) noexcept : fd_(o.fd_), data_(o.data_), size_(o.size_) {
    o.fd_ = -1;
    o.data_ = nullptr;
  }
  MappedFile& operator=(MappedFile&& o) noexcept {
    std::swap(fd_, o.fd_);
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    return *this;
  }
  ~MappedFile() {
    if (data_ != nullptr && data_ != MAP_FAILED) ::munmap(data_, size_);
    if (fd_ >= 0) ::close(fd_);
  }
  std::string_view bytes() const {
    return data_ == nullptr ? std::string_view() : std::string_view(static_cast<const char*>(data_), size_);
  }

 private:
  int fd_ = -1;
  void* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace

Result<HttpReply> stow(const HandlerContext& c, const std::string& study_uid, const HttpRequest& req) {
  const std::string content_type = req.header("Content-Type");
  if (!is_multipart_related(content_type))
    return HttpReply{
        415, "", error_body(invalid_argument("STOW-RS takes multipart/related; type=\"application/dicom\""), 415), {}};
  SOIQ_ASSIGN_OR_RETURN(TempDir dir, TempDir::create());  // removed with the files on return
  MappedFile mapped;
  if (!req.body_path.empty()) {
    SOIQ_ASSIGN_OR_RETURN(mapped, MappedFile::open(req.body_path));
  }
  SOIQ_ASSIGN_OR_RETURN(const ParsedMultipart body, parse_multipart_related(content_type, mapped.bytes(), kMaxParts));
  if (!body.type.empty() && body.type != "application/dicom")
    return HttpReply{415,
                     "",
                     error_body(invalid_argument("soiq stores application/dicom parts, not " + body.type +
                                                 " (send the DICOM files themselves)"),
                                415),
                     {}};
  if (body.parts.empty()) return invalid_argument("the request holds no DICOM part");
  for (const MultipartPart& p : body.parts) {
    if (!p.content_type.empty() && p.content_type.rfind("application/dicom", 0) != 0)
      return HttpReply{
          415, "", error_body(invalid_argument("a part is " + p.content_type + ", not application/dicom"), 415), {}};
  }

  std::vector<Part> parts(body.parts.size());
  std::vector<std::string> files;
  for (size_t i = 0; i < parts.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "part-%06zu.dcm", i + 1);
    parts[i].file = name;
    std::ofstream out(dir.path() + "/" + name, std::ios::binary);
    out.write(body.parts[i].bytes.data(), std::streamsize(body.parts[i].bytes.size()));
    if (!out) return internal_error("cannot write a received part to soiqd's temporary folder");
  }
  // Each part's identity, and those of another study than the URL names left out of the import.
  SOIQ_ASSIGN_OR_RETURN(const dicom::DicomScan scan, dicom::scan_dicom({dir.path()}));
  std::map<std::string, Part*> by_file;
  for (Part& p : parts) by_file[dir.path() + "/" + p.file] = &p;
  for (const dicom::DicomSeries& s : scan.series) {
    for (const dicom::DicomInstance& i : s.instances) {
      Part* p = by_file.count(i.path) ? by_file[i.path] : nullptr;
      if (p == nullptr) continue;
      *p = Part{p->file, i.sop_class_uid, i.sop_instance_uid, s.series_uid, s.study_uid, s.modality, true, 0, 0};
      if (!study_uid.empty() && s.study_uid != study_uid) {
        p->failure = kStudyMismatch;
        std::filesystem::remove(i.path);
      }
    }
  }
  for (const Part& p : parts)
    if (p.failure == 0) files.push_back(p.file);

  HttpReply reply;
  int warnings = 0;
  auto warn = [&](const std::string& text) {
    if (warnings++ < kMaxWarningHeaders) reply.headers.emplace("Warning", "299 soiqd \"" + one_line(text) + "\"");
  };
  if (!files.empty()) {
    auto work = [&]() -> Result<DicomImportResult> {
      return import_dicom_folder(c.engines.store, dir.path(), files, c.engines.config.max_grid_voxels, c.engines.budget,
                                 [] { return ok_status(); },
                                 {c.engines.config.keep_patient_names, false, c.engines.config.keep_instances});
    };
    Result<DicomImportResult> imported = c.engines.pool.call(work);
    if (!imported.ok() && imported.status().code() == StatusCode::kAlreadyExists) {
      // Nothing was stored: the parts whose UIDs are stored with other content are duplicates, the
      // others failed with them (an import is stored whole or not at all).
      const std::string& why = imported.status().message();
      for (Part& p : parts) {
        if (p.failure != 0) continue;
        const bool named = why.find("'" + p.series + "'") != std::string::npos ||
                           why.find("'" + p.sop_instance + "'") != std::string::npos;
        p.failure = named ? kDuplicateSopInstance : kProcessingFailure;
      }
      warn(why);
    } else if (!imported.ok()) {
      // Nothing was stored: every part failed, for the reason the import gives.
      if (imported.status().code() != StatusCode::kInvalidArgument &&
          imported.status().code() != StatusCode::kResourceExhausted)
        return imported.status();
      const int reason =
          imported.status().code() == StatusCode::kResourceExhausted ? kOutOfResources : kProcessingFailure;
      for (Part& p : parts)
        if (p.failure == 0) p.failure = p.read ? reason : kCannotUnderstand;
      warn(imported.status().message());
    } else {
      judge(parts, *imported);
      for (const ImportProblem& p : imported->problems) warn((p.path.empty() ? "" : p.path + ": ") + p.message);
      c.engines.queued_work();
    }
  }
  for (const Part& p : parts) {
    if (p.failure == kStudyMismatch)
      warn(p.file + ": study " + p.study + " is not the study " + study_uid + " the URL names");
    else if (p.failure == kCannotUnderstand)
      warn(p.file + ": not a DICOM file soiq can read");
    else if (p.failure == kSopClassNotSupported)
      warn(p.file + ": soiq keeps CT, MR and PET images, RT Structure Sets and SEGs, not " +
           (p.modality.empty() ? "this object" : p.modality));
  }

  json stored = json::array(), failed = json::array();
  for (const Part& p : parts) {
    if (p.failure != 0) {
      failed.push_back(reference(p, p.failure, "00081197"));
    } else {
      stored.push_back(reference(p, p.warning, "00081196"));
    }
  }
  json out = json::object();
  if (!study_uid.empty()) out["00081190"] = {{"vr", "UR"}, {"Value", {c.base_url + "/studies/" + study_uid}}};
  if (!failed.empty()) out["00081198"] = {{"vr", "SQ"}, {"Value", failed}};
  if (!stored.empty()) out["00081199"] = {{"vr", "SQ"}, {"Value", stored}};
  const bool any_warning = std::any_of(parts.begin(), parts.end(), [](const Part& p) { return p.warning != 0; });
  reply.status = stored.empty() ? 409 : (!failed.empty() || any_warning ? 202 : 200);
  reply.content_type = "application/dicom+json";
  reply.body = out.dump(-1, ' ', false, json::error_handler_t::replace);
  return reply;
}

}  // namespace soiq::server::http
