#include "client/read_token_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace soiq::client {

Result<std::string> read_token_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return not_found("cannot read token file '" + path + "': " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  std::string token = text.str();
  while (!token.empty() &&
         (token.back() == '\n' || token.back() == '\r' || token.back() == ' ' || token.back() == '\t')) {
    token.pop_back();
  }
  if (token.empty()) return invalid_argument("token file '" + path + "' is empty");
  for (const char c : token) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      return invalid_argument("token file '" + path +
                              "' holds a control character or a line break; put the token alone on one line");
    }
  }
  return token;
}

}  // namespace soiq::client
