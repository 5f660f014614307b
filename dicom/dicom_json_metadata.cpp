#include "dicom/dicom_json_metadata.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dcjson.h>
#include <dcmtk/dcmdata/dctk.h>

#include <memory>
#include <sstream>

#include "dicom/dcmtk_file.h"

namespace soiq::dicom {
namespace {

// Compact JSON with Pixel Data as a BulkDataURI (PS3.18: metadata carries no bulk data).
class MetadataFormat : public DcmJsonFormatCompact {
 public:
  explicit MetadataFormat(std::string uri) : DcmJsonFormatCompact(OFFalse), uri_(std::move(uri)) {}
  OFBool asBulkDataURI(const DcmTagKey& tag, OFString& uri) override {
    if (tag != DCM_PixelData) return OFFalse;
    uri = uri_.c_str();
    return OFTrue;
  }

 private:
  std::string uri_;
};

}  // namespace

Result<std::string> dicom_json_metadata(const std::string& part10, const std::string& bulk_data_uri) {
  SOIQ_ASSIGN_OR_RETURN(const std::unique_ptr<DcmFileFormat> file, parse_part10(part10));
  MetadataFormat format(bulk_data_uri);
  std::ostringstream out;
  const OFCondition c = file->getDataset()->writeJson(out, format);
  if (c.bad()) return internal_error(std::string("DCMTK could not write the metadata as JSON: ") + c.text());
  // DCMTK writes the dataset's members without the enclosing braces.
  return "{" + out.str() + "}";
}

std::string with_bulk_data_uri(std::string metadata, const std::string& bulk_data_uri) {
  // The placeholder is written by DCMTK as a JSON string value; no attribute value can hold it
  // quoted this way, since DCMTK escapes the quotes inside values.
  const std::string token = std::string("\"BulkDataURI\":\"") + kBulkDataUriPlaceholder + "\"";
  const size_t at = metadata.find(token);
  if (at != std::string::npos) metadata.replace(at, token.size(), "\"BulkDataURI\":\"" + bulk_data_uri + "\"");
  return metadata;
}

Result<std::string> pixel_data_of(const std::string& part10) {
  SOIQ_ASSIGN_OR_RETURN(const std::unique_ptr<DcmFileFormat> file, parse_part10(part10));
  const Uint8* bytes = nullptr;
  unsigned long count = 0;
  if (file->getDataset()->findAndGetUint8Array(DCM_PixelData, bytes, &count).bad() || bytes == nullptr)
    return not_found("the instance has no Pixel Data");
  return std::string(reinterpret_cast<const char*>(bytes), count);
}

}  // namespace soiq::dicom
