#include "server/util/temp_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace soiq::server {

Result<TempFile> TempFile::create(const std::string& suffix) {
  const char* dir = std::getenv("TMPDIR");
  std::string pattern = std::string(dir && *dir ? dir : "/tmp") + "/soiqd-XXXXXX" + suffix;
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  const int fd = mkstemps(buf.data(), static_cast<int>(suffix.size()));
  if (fd < 0) return internal_error("cannot create a temporary file '" + pattern + "': " + std::strerror(errno));
  close(fd);
  return TempFile(std::string(buf.data()));
}

TempFile::~TempFile() {
  if (!path_.empty()) unlink(path_.c_str());
}

Status TempFile::write(const std::string& bytes) const {
  std::ofstream out(path_, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) return internal_error("cannot write the temporary file " + path_ + " (disk full?)");
  return ok_status();
}

Result<std::string> TempFile::read() const {
  std::ifstream in(path_, std::ios::binary);
  if (!in) return internal_error("cannot read the temporary file " + path_);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace soiq::server
