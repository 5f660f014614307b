// Feeds each input to what soiqd's HTTP API parses from a client before any store is touched: the
// first line as a multipart/related boundary and the rest as a STOW-RS body
// (parse_multipart_related), and the whole input as a query string (split at '&' and '='), to the
// QIDO-RS query at each level (parse_qido) and to /soiq/v1/query's arguments
// (parse_soiq_query_args). A bug is any crash or sanitizer report, a run over -timeout, or a broken
// contract: every part must lie inside the body, and parts written back (write_multipart_related)
// must read back as the same parts.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/require.h"
#include "server/http/multipart.h"
#include "server/http/qido_query.h"
#include "server/http/soiq_query_args.h"

namespace {

using soiq::server::http::QueryParams;

QueryParams query_params(const std::string& text) {
  QueryParams out;
  size_t from = 0;
  while (from <= text.size() && out.size() < 64) {
    size_t amp = text.find('&', from);
    if (amp == std::string::npos) amp = text.size();
    const std::string pair = text.substr(from, amp - from);
    const size_t eq = pair.find('=');
    out.emplace_back(pair.substr(0, eq), eq == std::string::npos ? "" : pair.substr(eq + 1));
    from = amp + 1;
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace http = soiq::server::http;
  const std::string text(reinterpret_cast<const char*>(data), size);

  const size_t newline = text.find('\n');
  const std::string boundary = text.substr(0, newline);
  const std::string body = newline == std::string::npos ? "" : text.substr(newline + 1);
  auto parsed =
      http::parse_multipart_related("multipart/related; type=\"application/dicom\"; boundary=" + boundary, body, 1000);
  if (parsed.ok()) {
    std::vector<std::string_view> parts;
    for (const http::MultipartPart& p : parsed->parts) {
      soiq::fuzz::require(p.bytes.data() >= body.data() && p.bytes.data() + p.bytes.size() <= body.data() + body.size(),
                          "a part lies outside the body");
      parts.push_back(p.bytes);
    }
    const http::WrittenMultipart w = http::write_multipart_related({parts.begin(), parts.end()}, "application/dicom");
    const std::string written = w.body();
    auto again = http::parse_multipart_related("multipart/related; boundary=" + w.boundary, written, 1000);
    soiq::fuzz::require(again.ok() && again->parts.size() == parts.size(), "written parts do not read back");
    for (size_t i = 0; i < parts.size(); ++i)
      soiq::fuzz::require(again->parts[i].bytes == parts[i], "a part read back differs");
  }

  const QueryParams params = query_params(text);
  for (const auto level : {http::QidoLevel::kStudy, http::QidoLevel::kSeries, http::QidoLevel::kInstance}) {
    (void)http::parse_qido(level, "", "", params, true);
    (void)http::parse_qido(level, "1.2.3", "4.5.6", params, false);
  }
  (void)http::parse_soiq_query_args(params);
  return 0;
}
