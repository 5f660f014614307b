#include "dicom/dicom_value_fits.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcvrda.h>
#include <dcmtk/dcmdata/dcvrsh.h>
#include <dcmtk/dcmdata/dcvrtm.h>

#include <algorithm>

namespace soiq::dicom {

bool fits_date(const std::string& v) { return DcmDate::checkStringValue(v.c_str(), "1").good(); }

bool fits_time(const std::string& v) { return DcmTime::checkStringValue(v.c_str(), "1").good(); }

bool fits_short_string(const std::string& v) {
  // DCMTK 3.6.7 leaves SH's length unchecked: checked here.
  return v.size() <= 16 &&
         std::all_of(v.begin(), v.end(), [](unsigned char ch) { return ch >= 0x20 && ch < 0x7F && ch != '\\'; }) &&
         DcmShortString::checkStringValue(v.c_str(), "1").good();
}

bool fits_long_string(const std::string& v) {
  return v.size() <= 64 &&
         std::none_of(v.begin(), v.end(), [](char ch) { return ch == '\\' || static_cast<unsigned char>(ch) < 0x20; });
}

}  // namespace soiq::dicom
