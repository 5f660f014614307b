#include "core/io/file_extension.h"

#include <algorithm>
#include <cctype>

namespace soiq {

std::string file_extension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (name.size() > 7 && name.ends_with(".nii.gz")) return ".nii.gz";
  const size_t dot = name.find_last_of('.');
  // A leading dot is a hidden file's name, not an extension.
  if (dot == std::string::npos || dot == 0) return "";
  return name.substr(dot);
}

}  // namespace soiq
