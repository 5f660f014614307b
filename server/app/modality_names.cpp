#include "server/app/modality_names.h"

#include <algorithm>
#include <cctype>

namespace soiq::server {

bool same_modality(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](unsigned char x, unsigned char y) {
           return std::toupper(x) == std::toupper(y);
         });
}

std::string dicom_modality(const std::string& name) { return same_modality(name, "PET") ? "PT" : name; }

bool is_series_uid(const std::string& ref) {
  return !ref.empty() && ref.find('.') != std::string::npos &&
         std::all_of(ref.begin(), ref.end(), [](char c) { return c == '.' || (c >= '0' && c <= '9'); });
}

}  // namespace soiq::server
