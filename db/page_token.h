#pragma once
// Opaque page tokens for keyset paging: a token carries the list it belongs to and the key of the
// last item of the previous page; the next page starts strictly after that key. Tokens stay valid
// across inserts and deletes (nothing is skipped or repeated that existed throughout) and never
// expire. Their text is hex so it survives any transport.

#include <string>
#include <string_view>

#include "core/base/status.h"

namespace soiq::db {

// The page size to use: 0 -> 100, above 1000 -> 1000. INVALID_ARGUMENT when negative.
Result<int> effective_page_size(int32_t requested);

std::string make_page_token(std::string_view list, std::string_view last_key);

// The last key in `token`, "" for an empty token (the first page). INVALID_ARGUMENT when the token
// is malformed or was made for another list.
Result<std::string> parse_page_token(std::string_view list, const std::string& token);

}  // namespace soiq::db
