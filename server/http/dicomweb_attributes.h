#pragma once
// The DICOM attributes soiq's DICOMweb answers with and matches on (PS3.18 10.6, QIDO-RS), each
// named by tag and keyword, with its VR, the query level it belongs to, whether QIDO returns it
// without being asked (PS3.18 Table 10.6.3-3 to -5) and whether soiq can match on it.
//
// Input    an attribute ID as QIDO writes it: a keyword ("PatientID") or eight hex digits
//          ("00100020", any case).
// Output   the attribute, or nullptr when soiq has no such attribute (an unknown keyword, a
//          sequence path, an attribute soiq does not keep).
// Cost     a scan of ~30 entries; no allocation besides the upper-casing of a tag.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace soiq::server::http {

enum class QidoLevel { kStudy, kSeries, kInstance };

struct DicomAttribute {
  uint32_t tag;         // group << 16 | element
  const char* keyword;  // DICOM's keyword (PS3.6)
  const char* vr;       // the VR its JSON carries
  QidoLevel level;      // the level whose entity holds it
  bool default_return;  // returned without includefield
  bool matchable;       // a QIDO query key soiq can match on
};

const DicomAttribute* find_attribute(std::string_view id);
// Every attribute of the table, in tag order.
const std::vector<DicomAttribute>& dicomweb_attributes();
// "0020000D": the tag as DICOM JSON names it.
std::string tag_key(uint32_t tag);

// The tags soiq's answers use by name.
namespace tags {
inline constexpr uint32_t kSpecificCharacterSet = 0x00080005;
inline constexpr uint32_t kStudyDate = 0x00080020;
inline constexpr uint32_t kStudyTime = 0x00080030;
inline constexpr uint32_t kAccessionNumber = 0x00080050;
inline constexpr uint32_t kInstanceAvailability = 0x00080056;
inline constexpr uint32_t kModalitiesInStudy = 0x00080061;
inline constexpr uint32_t kSopClassUid = 0x00080016;
inline constexpr uint32_t kSopInstanceUid = 0x00080018;
inline constexpr uint32_t kModality = 0x00080060;
inline constexpr uint32_t kReferringPhysicianName = 0x00080090;
inline constexpr uint32_t kStudyDescription = 0x00081030;
inline constexpr uint32_t kSeriesDescription = 0x0008103E;
inline constexpr uint32_t kRetrieveUrl = 0x00081190;
inline constexpr uint32_t kPatientName = 0x00100010;
inline constexpr uint32_t kPatientId = 0x00100020;
inline constexpr uint32_t kPatientBirthDate = 0x00100030;
inline constexpr uint32_t kPatientSex = 0x00100040;
inline constexpr uint32_t kPatientAge = 0x00101010;
inline constexpr uint32_t kStudyInstanceUid = 0x0020000D;
inline constexpr uint32_t kSeriesInstanceUid = 0x0020000E;
inline constexpr uint32_t kStudyId = 0x00200010;
inline constexpr uint32_t kSeriesNumber = 0x00200011;
inline constexpr uint32_t kInstanceNumber = 0x00200013;
inline constexpr uint32_t kFrameOfReferenceUid = 0x00200052;
inline constexpr uint32_t kNumberOfStudyRelatedSeries = 0x00201206;
inline constexpr uint32_t kNumberOfStudyRelatedInstances = 0x00201208;
inline constexpr uint32_t kNumberOfSeriesRelatedInstances = 0x00201209;
inline constexpr uint32_t kRows = 0x00280010;
inline constexpr uint32_t kColumns = 0x00280011;
}  // namespace tags

}  // namespace soiq::server::http
