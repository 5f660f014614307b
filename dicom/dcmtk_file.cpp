#include "dicom/dcmtk_file.h"

#include <dcmtk/dcmdata/dcistrmb.h>
#include <dcmtk/dcmdata/dcostrmb.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>

namespace soiq::dicom {

bool looks_like_dicom(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[132] = {};
  in.read(reinterpret_cast<char*>(b), sizeof b);
  const std::streamsize n = in.gcount();
  if (n == 132 && b[128] == 'D' && b[129] == 'I' && b[130] == 'C' && b[131] == 'M') return true;
  if (n < 8) return false;
  // A bare dataset starts with its lowest tag; groups 0002 (meta), 0004 (DICOMDIR), 0008 (identity).
  const auto plausible = [](unsigned group, unsigned element) {
    return (group == 0x0002 || group == 0x0004 || group == 0x0008) && element < 0x1000;
  };
  const unsigned group_le = b[0] | (b[1] << 8), element_le = b[2] | (b[3] << 8);
  const unsigned group_be = (b[0] << 8) | b[1], element_be = (b[2] << 8) | b[3];
  return plausible(group_le, element_le) || plausible(group_be, element_be);
}

Status condition_status(StatusCode code, const std::string& path, const std::string& what, const OFCondition& cond) {
  return Status(code, "'" + path + "': " + what + " (" + cond.text() + ")");
}

Result<std::unique_ptr<DcmFileFormat>> load_dicom_file(const std::string& path, bool until_pixel_data) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return not_found("'" + path + "': no such file");
  // DCMTK logs its warnings (e.g. "PixelData encountered, skipping rest of dataset" for every
  // header-only read) to stderr; what matters reaches the caller as a Status instead.
  static std::once_flag quiet;
  std::call_once(quiet, [] { DCM_dcmdataLogger.setLogLevel(OFLogger::FATAL_LOG_LEVEL); });
  auto file = std::make_unique<DcmFileFormat>();
  const OFCondition cond =
      file->loadFileUntilTag(path.c_str(), EXS_Unknown, EGL_noChange, DCM_MaxReadLength, ERM_autoDetect,
                             until_pixel_data ? DCM_PixelData : DCM_UndefinedTagKey);
  if (cond.bad()) return condition_status(StatusCode::kDataLoss, path, "not a readable DICOM file", cond);
  // Every text soiq keeps is UTF-8 (core/base/field_rules.h), so the character set is converted
  // before any value is read: a study description in Latin-1 (ISO_IR 100) or a Japanese name (ISO 2022
  // IR 87) arrives as the same characters in UTF-8. Where DCMTK cannot convert, the values stay as they
  // are and each reader's rules drop the ones that are not UTF-8 rather than store them garbled.
  DcmDataset& ds = *file->getDataset();
  const std::string charset = get_string(ds, DCM_SpecificCharacterSet);
  if (!charset.empty() && charset != "ISO_IR 192" && charset != "ISO_IR 6") (void)ds.convertToUTF8();
  return file;
}

std::string get_string(DcmItem& item, const DcmTagKey& tag, unsigned long pos) {
  OFString value;
  if (item.findAndGetOFString(tag, value, pos).bad()) return "";
  std::string s(value.c_str());
  const auto first = s.find_first_not_of(" \0", 0, 2);
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \0", std::string::npos, 2);
  return s.substr(first, last - first + 1);
}

std::string get_string_array(DcmItem& item, const DcmTagKey& tag) {
  // The stored value as one string. Not findAndGetOFStringArray: it fetches value n by re-counting
  // the values from the start each time, O(values^2): 60 % of an STS import went to the Contour
  // Data of the RT Structure Sets (thousands of numbers per contour).
  const char* value = nullptr;
  Uint32 length = 0;
  if (item.findAndGetString(tag, value, length).bad() || value == nullptr) return "";
  std::string s(value, length);
  const auto first = s.find_first_not_of(" \0", 0, 2);
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \0", std::string::npos, 2);
  return s.substr(first, last - first + 1);
}

std::optional<double> get_number(DcmItem& item, const DcmTagKey& tag, unsigned long pos) {
  const std::string s = get_string(item, tag, pos);
  if (s.empty()) {
    // Binary VRs (FL, FD, US) have no string form in some DCMTK paths: ask for a double directly.
    Float64 v = 0;
    if (item.findAndGetFloat64(tag, v, pos).good()) return v;
    return std::nullopt;
  }
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str()) return std::nullopt;
  return v;
}

std::optional<std::vector<double>> get_numbers(DcmItem& item, const DcmTagKey& tag, unsigned long count) {
  std::vector<double> out;
  for (unsigned long i = 0; i < count; ++i) {
    const auto v = get_number(item, tag, i);
    if (!v) return std::nullopt;
    out.push_back(*v);
  }
  return out;
}

Result<std::unique_ptr<DcmFileFormat>> parse_part10(const std::string& part10) {
  DcmInputBufferStream in;
  in.setBuffer(part10.data(), offile_off_t(part10.size()));
  in.setEos();
  auto file = std::make_unique<DcmFileFormat>();
  file->transferInit();
  const OFCondition c = file->read(in, EXS_Unknown, EGL_noChange, DCM_MaxReadLength);
  file->transferEnd();
  if (c.bad()) return invalid_argument(std::string("not a DICOM file: ") + c.text());
  return file;
}

Result<std::string> part10_bytes(DcmFileFormat& file) {
  std::string out;
  std::vector<char> buffer(1 << 20);
  DcmOutputBufferStream stream(buffer.data(), static_cast<offile_off_t>(buffer.size()));
  file.transferInit();
  OFCondition c = EC_StreamNotifyClient;
  while (c == EC_StreamNotifyClient) {
    c = file.write(stream, EXS_LittleEndianExplicit, EET_ExplicitLength, nullptr);
    void* data = nullptr;
    offile_off_t length = 0;
    stream.flushBuffer(data, length);  // whatever the buffer holds, full or final
    out.append(static_cast<const char*>(data), static_cast<size_t>(length));
  }
  file.transferEnd();
  if (c.bad()) return internal_error(std::string("DICOM: encoding the file: ") + c.text());
  return out;
}

}  // namespace soiq::dicom
