#pragma once
// multipart/related bodies (RFC 2387), as WADO-RS answers and STOW-RS requests carry DICOM
// instances (PS3.18 8.6.1.2): soiq writes them for WADO and reads them for STOW. HTTP libraries
// parse multipart/form-data at most, so this is soiq's own, small and strict.
//
// Reading
//   Input   the Content-Type header's value and the body.
//   Output  each part's Content-Type (lower-case, parameters kept as sent, "" when the part has
//           none) and its bytes, as views into `body` (valid while it lives).
//   Errors  INVALID_ARGUMENT for a Content-Type without a boundary, a body without it, a part
//           without its header end, more than max_parts parts, or part headers over 8 KiB. (A
//           Content-Type that is not multipart/related at all is the caller's 415:
//           is_multipart_related.)
// Writing
//   Output  the body as pieces to send back to back (each delimiter, then the part itself, moved
//           in, not copied: a WADO answer of many SEGs is held once), and the boundary to put in
//           the reply's Content-Type (random, checked against the parts so it occurs in none).
// Cost     O(body); no copy of part bytes on reading.

#include <string>
#include <string_view>
#include <vector>

#include "core/base/status.h"

namespace soiq::server::http {

struct MultipartPart {
  std::string content_type;
  std::string_view bytes;
};

struct ParsedMultipart {
  std::string type;  // the related type parameter, e.g. "application/dicom" ("" when absent)
  std::vector<MultipartPart> parts;
};

bool is_multipart_related(const std::string& content_type);

Result<ParsedMultipart> parse_multipart_related(const std::string& content_type, std::string_view body,
                                                size_t max_parts);

struct WrittenMultipart {
  std::string boundary;
  std::vector<std::string> pieces;
  std::string body() const;  // the pieces joined (for tests; answers send the pieces)
};

WrittenMultipart write_multipart_related(std::vector<std::string> parts, const std::string& part_type);

// Writing as the parts come, for an answer too large to hold at once (a series' instances, sent
// one at a time): a random boundary first (160 bits, so that no part holds it but by a chance
// nobody will see; each part is checked against it all the same, INTERNAL then), then each part's
// delimiter and header, its bytes, and the close delimiter.
std::string random_boundary();
// What goes before a part's bytes; `first` for the first part of the body.
std::string multipart_part_head(const std::string& boundary, const std::string& part_type, bool first);
Status check_part_against_boundary(const std::string& boundary, std::string_view part);
// The end of the body; `any_part` false for a body of no part.
std::string multipart_close(const std::string& boundary, bool any_part);

// The value of parameter `name` of a header value such as 'multipart/related; type="a/b"' ("" when
// absent), unquoted; names compare ignoring case.
std::string header_parameter(const std::string& value, const std::string& name);

}  // namespace soiq::server::http
