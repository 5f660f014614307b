#include "core/io/write_file_bytes.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace soiq {

Status write_error(const std::string& path, int err, const std::string& what) {
  const std::string why = std::strerror(err);
  if (err == ENOENT || err == ENOTDIR) {
    return not_found("cannot write " + what + " '" + path + "': its directory does not exist (" + why + ")");
  }
  if (err == ENOSPC || err == EDQUOT) return resource_exhausted("cannot write " + what + " '" + path + "': " + why);
  return internal_error("cannot write " + what + " '" + path + "': " + why);
}

Status write_file_bytes(const std::string& path, std::string_view bytes, const std::string& what) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  FILE* file = std::fopen(tmp.c_str(), "wb");
  if (!file) return write_error(path, errno, what);
  const size_t written = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), file);
  int err = written == bytes.size() ? 0 : errno;
  if (std::fflush(file) != 0 && err == 0) err = errno;
  if (std::fclose(file) != 0 && err == 0) err = errno;
  if (err == 0 && std::rename(tmp.c_str(), path.c_str()) != 0) err = errno;
  if (err != 0) {
    std::remove(tmp.c_str());
    return write_error(path, err, what);
  }
  return ok_status();
}

}  // namespace soiq
