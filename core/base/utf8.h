#pragma once
// Whether bytes are well-formed UTF-8, as JSON, PostgreSQL's text and DICOM's ISO_IR 192 need.
//
// Input    any bytes.
// Output   true for RFC 3629 UTF-8: no overlong forms, no surrogates (U+D800..U+DFFF), nothing
//          past U+10FFFF, no truncated sequence. "" is UTF-8.
// Cost     O(bytes); no allocation.

#include <string_view>

namespace soiq {

bool is_utf8(std::string_view text);

}  // namespace soiq
