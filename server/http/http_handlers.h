#pragma once
// The DICOMweb and /soiq/v1 handlers behind server/http/dicomweb_server.cpp, one file per service
// (qido_handlers.cpp, …). Each turns a request into calls on the shared engines and returns the
// reply or a Status, which the server maps to HTTP once (http_status.h); none writes to the socket.

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "server/app/app_engines.h"
#include "server/http/dicomweb_attributes.h"
#include "server/http/http_reply.h"
#include "server/http/http_request.h"

namespace soiq::server::http {

// What every handler gets besides the request: the engines and the URL prefix of this server's
// DICOMweb resources ("http://host:port/dicom-web"), for RetrieveURL.
struct HandlerContext {
  const AppEngines& engines;
  std::string base_url;
};

// Whether the request's Accept header admits `type` (absent, */*, type/* and the type itself do;
// q-values are not weighed). NOT_ACCEPTABLE is not a Status code: the caller replies 406.
bool accepts(const HttpRequest& req, const std::string& type);
// The media types of the Accept header in the client's order, parameters and spaces dropped
// ("image/png", "*/*"); empty without the header.
std::vector<std::string> accepted_types(const HttpRequest& req);

// Each item of the Accept header, in the client's order: its media type (lower-case, spaces
// trimmed) and the `type` and `transfer-syntax` parameters DICOMweb's multipart types carry ("" when
// absent), unquoted. Empty without the header.
struct AcceptItem {
  std::string media, type, transfer_syntax;
};
std::vector<AcceptItem> accept_items(const HttpRequest& req);

// What a long handler checks between steps: CANCELLED once the client has closed its connection
// (its work is not worth finishing).
std::function<Status()> stop_when_client_gone(const HttpRequest& req);

// The rows of `query` as the engine gives them, whole (the answers that need every row: JSON, CSV,
// the plot); the summary too.
struct QueryAnswer {
  std::vector<QueryRow> rows;
  QuerySummary summary;
};
Result<QueryAnswer> run_query(const AppEngines& engines, const Query& query, const HttpRequest& req);

// QIDO-RS: GET /dicom-web/studies, /series, /instances and below a study or series.
Result<HttpReply> qido(const HandlerContext& c, QidoLevel level, const std::string& study_uid,
                       const std::string& series_uid, const HttpRequest& req);

// WADO-RS: the SEG series of structures and the kept instances of image series (wado_images.h), as
// DICOM (multipart/related), as metadata (DICOM JSON, Pixel Data as a BulkDataURI), the Pixel Data
// itself (bulkdata) or an image instance's frames (`frames`: "1,2"). series_uid and instance_uid
// "" for a whole study or series.
enum class WadoWhat { kInstances, kMetadata, kBulkData, kFrames };
Result<HttpReply> wado(const HandlerContext& c, WadoWhat what, const std::string& study_uid,
                       const std::string& series_uid, const std::string& instance_uid, const std::string& frames,
                       const HttpRequest& req);

// GET /soiq/v1/query: the two-stage query with soiq query's options as arguments; JSON rows, or CSV
// with Accept: text/csv.
Result<HttpReply> soiq_query(const HandlerContext& c, const HttpRequest& req);

// WADO-RS rendered and thumbnail resources of a study (thumbnail only), series, instance or one
// frame (`frames` "" for none): PNG or JPEG with window, viewport and quality.
Result<HttpReply> wado_rendered(const HandlerContext& c, bool thumbnail, const std::string& study_uid,
                                const std::string& series_uid, const std::string& instance_uid,
                                const std::string& frames, const HttpRequest& req);

// GET /soiq/v1/query/plot: the query's histogram or scatter, SVG or PNG.
Result<HttpReply> soiq_query_plot(const HandlerContext& c, const HttpRequest& req);

// GET /soiq/v1/structures/{id}/{rendered|thumbnail|seg|mask|surface}.
enum class StructureResource { kRendered, kThumbnail, kSeg, kMask, kSurface };
Result<HttpReply> soiq_structure(const HandlerContext& c, StructureResource what, const std::string& id,
                                 const HttpRequest& req);

// GET /soiq/v1/info: the feature catalogue, the query options and the viewer link, as JSON (the
// query page's form).
Result<HttpReply> soiq_info(const HandlerContext& c, const HttpRequest& req);

// STOW-RS: POST /dicom-web/studies[/{study}] with multipart/related DICOM, imported as ImportDicom
// imports files; study_uid "" takes any study. The body is the file the connection received it
// into (req.body_path), read through a mapping, never held in memory.
Result<HttpReply> stow(const HandlerContext& c, const std::string& study_uid, const HttpRequest& req);

}  // namespace soiq::server::http
