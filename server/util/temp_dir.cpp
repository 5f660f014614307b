#include "server/util/temp_dir.h"

#include <stdlib.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

namespace soiq::server {

Result<TempDir> TempDir::create() {
  const char* dir = std::getenv("TMPDIR");
  const std::string pattern = std::string(dir && *dir ? dir : "/tmp") + "/soiqd-import-XXXXXX";
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  if (mkdtemp(buf.data()) == nullptr)
    return internal_error("cannot create a temporary directory '" + pattern + "': " + std::strerror(errno));
  return TempDir(std::string(buf.data()));
}

TempDir::~TempDir() {
  if (path_.empty()) return;
  std::error_code ignored;  // a destructor cannot report; a leftover directory is harmless
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace soiq::server
