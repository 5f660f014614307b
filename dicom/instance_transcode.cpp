#include "dicom/instance_transcode.h"

#include "dicom/dcmtk_file.h"
#include "dicom/decompress_pixels.h"

namespace soiq::dicom {

Result<std::string> transfer_syntax_of(const std::string& part10) {
  SOIQ_ASSIGN_OR_RETURN(const std::unique_ptr<DcmFileFormat> file, parse_part10(part10));
  const std::string uid = get_string(*file->getMetaInfo(), DCM_TransferSyntaxUID);
  if (uid.empty()) return invalid_argument("the instance has no Transfer Syntax UID in its meta header");
  return uid;
}

Result<std::string> as_explicit_little_endian(std::string part10) {
  SOIQ_ASSIGN_OR_RETURN(const std::unique_ptr<DcmFileFormat> file, parse_part10(part10));
  if (get_string(*file->getMetaInfo(), DCM_TransferSyntaxUID) == kExplicitVrLittleEndianUid) return part10;
  SOIQ_RETURN_IF_ERROR(decompress_pixels(*file->getDataset(), "the instance"));
  // part10_bytes writes the meta header anew, with the new transfer syntax.
  file->getMetaInfo()->findAndDeleteElement(DCM_TransferSyntaxUID);
  return part10_bytes(*file);
}

}  // namespace soiq::dicom
