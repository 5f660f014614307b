#pragma once
// The bearer token of a token file: its content without trailing whitespace (a file written by
// `echo` ends in a newline).
// Errors: NOT_FOUND when the file cannot be read (the message names it); INVALID_ARGUMENT when it
// is empty or the token holds a line break or a control character (it would not be valid metadata).

#include <string>

#include "core/base/status.h"

namespace soiq::client {

Result<std::string> read_token_file(const std::string& path);

}  // namespace soiq::client
