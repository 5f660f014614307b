#include "server/app/modality_names.h"

#include <algorithm>
#include <cctype>

namespace soiq::server {

std::string dicom_modality(const std::string& name) {
  std::string upper = name;
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return upper == "PET" ? "PT" : name;
}

bool is_series_uid(const std::string& ref) {
  return !ref.empty() && ref.find('.') != std::string::npos &&
         std::all_of(ref.begin(), ref.end(), [](char c) { return c == '.' || (c >= '0' && c <= '9'); });
}

}  // namespace soiq::server
