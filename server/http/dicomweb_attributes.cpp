#include "server/http/dicomweb_attributes.h"

#include <cstdio>

namespace soiq::server::http {

const std::vector<DicomAttribute>& dicomweb_attributes() {
  using L = QidoLevel;
  // Matchable: the keys server/http/qido_query.cpp turns into store searches. The rest are answered
  // (by default or through includefield) but not matched: a query on them is refused, not ignored.
  static const std::vector<DicomAttribute> kAttributes = {
      {tags::kSpecificCharacterSet, "SpecificCharacterSet", "CS", L::kStudy, true, false},
      {tags::kSopClassUid, "SOPClassUID", "UI", L::kInstance, true, false},
      {tags::kSopInstanceUid, "SOPInstanceUID", "UI", L::kInstance, true, true},
      {tags::kStudyDate, "StudyDate", "DA", L::kStudy, true, true},
      {tags::kStudyTime, "StudyTime", "TM", L::kStudy, true, false},
      {tags::kAccessionNumber, "AccessionNumber", "SH", L::kStudy, true, true},
      {tags::kInstanceAvailability, "InstanceAvailability", "CS", L::kStudy, true, false},
      {tags::kModality, "Modality", "CS", L::kSeries, true, true},
      {tags::kModalitiesInStudy, "ModalitiesInStudy", "CS", L::kStudy, true, true},
      {tags::kReferringPhysicianName, "ReferringPhysicianName", "PN", L::kStudy, true, false},
      {tags::kStudyDescription, "StudyDescription", "LO", L::kStudy, false, false},
      {tags::kSeriesDescription, "SeriesDescription", "LO", L::kSeries, false, false},
      {tags::kRetrieveUrl, "RetrieveURL", "UR", L::kStudy, true, false},
      {tags::kPatientName, "PatientName", "PN", L::kStudy, true, true},
      {tags::kPatientId, "PatientID", "LO", L::kStudy, true, true},
      {tags::kPatientBirthDate, "PatientBirthDate", "DA", L::kStudy, true, false},
      {tags::kPatientSex, "PatientSex", "CS", L::kStudy, true, false},
      {tags::kPatientAge, "PatientAge", "AS", L::kStudy, false, false},
      {tags::kStudyInstanceUid, "StudyInstanceUID", "UI", L::kStudy, true, true},
      {tags::kSeriesInstanceUid, "SeriesInstanceUID", "UI", L::kSeries, true, true},
      {tags::kStudyId, "StudyID", "SH", L::kStudy, true, true},
      {tags::kSeriesNumber, "SeriesNumber", "IS", L::kSeries, true, false},
      {tags::kInstanceNumber, "InstanceNumber", "IS", L::kInstance, true, false},
      {tags::kFrameOfReferenceUid, "FrameOfReferenceUID", "UI", L::kSeries, false, false},
      {tags::kNumberOfStudyRelatedSeries, "NumberOfStudyRelatedSeries", "IS", L::kStudy, true, false},
      {tags::kNumberOfStudyRelatedInstances, "NumberOfStudyRelatedInstances", "IS", L::kStudy, true, false},
      {tags::kNumberOfSeriesRelatedInstances, "NumberOfSeriesRelatedInstances", "IS", L::kSeries, true, false},
      {tags::kRows, "Rows", "US", L::kInstance, true, false},
      {tags::kColumns, "Columns", "US", L::kInstance, true, false},
  };
  return kAttributes;
}

std::string tag_key(uint32_t tag) {
  char out[9];
  std::snprintf(out, sizeof out, "%08X", unsigned(tag));
  return out;
}

namespace {

bool is_hex_tag(std::string_view id) {
  if (id.size() != 8) return false;
  for (const char c : id) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'))) return false;
  }
  return true;
}

}  // namespace

const DicomAttribute* find_attribute(std::string_view id) {
  const bool hex = is_hex_tag(id);
  const uint32_t tag = hex ? uint32_t(std::stoul(std::string(id), nullptr, 16)) : 0;
  for (const DicomAttribute& a : dicomweb_attributes()) {
    if (hex ? a.tag == tag : id == a.keyword) return &a;
  }
  return nullptr;
}

}  // namespace soiq::server::http
