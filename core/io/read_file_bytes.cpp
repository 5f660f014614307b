#include "core/io/read_file_bytes.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

namespace soiq {

Result<int64_t> input_file_size(const std::string& path, const std::string& what) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return not_found(what + " file '" + path + "' does not exist");
  if (std::filesystem::is_directory(status)) {
    return invalid_argument(what + " path '" + path + "' is a directory, not a file");
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return invalid_argument("cannot read the size of " + what + " file '" + path + "': " + ec.message());
  return int64_t(size);
}

Result<std::string> read_file_bytes(const std::string& path, const std::string& what, int64_t max_bytes) {
  SOIQ_ASSIGN_OR_RETURN(const int64_t size, input_file_size(path, what));
  if (size > max_bytes) {
    return resource_exhausted(what + " file '" + path + "' has " + std::to_string(size) +
                              " bytes, more than the limit of " + std::to_string(max_bytes));
  }
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) return not_found("cannot open " + what + " file '" + path + "'");
  std::string bytes(size_t(size), '\0');
  const size_t got = size == 0 ? 0 : std::fread(bytes.data(), 1, bytes.size(), file.get());
  if (got != bytes.size()) {
    return invalid_argument("cannot read " + what + " file '" + path + "': got " + std::to_string(got) + " of " +
                            std::to_string(size) + " bytes");
  }
  return bytes;
}

}  // namespace soiq
