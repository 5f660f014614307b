// The modules write_seg fills in besides the frames: who and what the SEG is about (Patient, Study,
// Frame of Reference, Series, SOP Common), its Segment Sequence, and the slices it references.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmiod/cielabutil.h>
#include <dcmtk/dcmiod/iodreferences.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "dicom/dicom_value_fits.h"
#include "dicom/seg_export_steps.h"

namespace soiq::dicom {
namespace {

DcmSegTypes::E_SegmentAlgoType algo_type(SegAlgorithmType t) {
  switch (t) {
    case SegAlgorithmType::kManual:
      return DcmSegTypes::SAT_MANUAL;
    case SegAlgorithmType::kSemiautomatic:
      return DcmSegTypes::SAT_SEMIAUTOMATIC;
    case SegAlgorithmType::kAutomatic:
      return DcmSegTypes::SAT_AUTOMATIC;
  }
  return DcmSegTypes::SAT_UNKNOWN;
}

}  // namespace

Status set_identity(DcmSegmentation& seg, const SegSource& src, const SegWriteOptions& options,
                    const std::string& series_uid, const std::string& sop_uid) {
  const std::string sex =
      src.patient_sex == "M" || src.patient_sex == "F" || src.patient_sex == "O" ? src.patient_sex : "";
  const std::string birth_date = type2_value(src.patient_birth_date, fits_date(src.patient_birth_date));
  const std::string study_date = type2_value(src.study_date, fits_date(src.study_date));
  const std::string study_time = type2_value(src.study_time, fits_time(src.study_time));
  const std::string study_id = type2_value(src.study_id, fits_short_string(src.study_id));
  const std::string accession = type2_value(src.accession_number, fits_short_string(src.accession_number));
  // checkValue=OFFalse: the patient id is the key that links the SEG to its images, copied even
  // where DCMTK's VR checks would reject it (e.g. a trailing backslash that PACS happily store);
  // the other values were checked above.
  IODPatientModule& patient = seg.getPatient();
  OFCondition c = patient.setPatientID(src.patient_id.c_str(), OFFalse);
  if (c.good()) c = patient.setPatientName(src.patient_name.c_str(), OFFalse);
  if (c.good()) c = patient.setPatientSex(sex.c_str(), OFFalse);
  if (c.good()) c = patient.setPatientBirthDate(birth_date.c_str(), OFFalse);
  IODGeneralStudyModule& study = seg.getStudy();
  if (c.good()) c = study.setStudyInstanceUID(src.study_uid.c_str(), OFFalse);
  if (c.good()) c = study.setStudyDate(study_date.c_str(), OFFalse);
  if (c.good()) c = study.setStudyTime(study_time.c_str(), OFFalse);
  if (c.good()) c = study.setStudyID(study_id.c_str(), OFFalse);
  if (c.good()) c = study.setAccessionNumber(accession.c_str(), OFFalse);
  if (c.good()) c = seg.getFrameOfReference().setFrameOfReferenceUID(src.frame_of_reference_uid.c_str(), OFFalse);
  if (c.good()) c = seg.getSeries().setSeriesInstanceUID(series_uid.c_str());
  if (c.good()) c = seg.getSeries().setSeriesDescription(options.series_description.c_str(), OFFalse);
  if (c.good()) c = seg.getSegmentationSeriesModule().setSeriesNumber(std::to_string(options.series_number).c_str());
  if (c.good()) c = seg.getSOPCommon().setSOPInstanceUID(sop_uid.c_str());
  if (c.bad())
    return invalid_argument("DICOM SEG: a patient, study or series value was refused (" + std::string(c.text()) + ")");
  return ok_status();
}

Status add_segment(DcmSegmentation& seg, const SegSegmentDescription& s) {
  DcmSegment* raw = nullptr;
  OFCondition c = DcmSegment::create(
      raw, s.label.c_str(),
      CodeSequenceMacro(s.category.value.c_str(), s.category.scheme.c_str(), s.category.meaning.c_str()),
      CodeSequenceMacro(s.type.value.c_str(), s.type.scheme.c_str(), s.type.meaning.c_str()),
      algo_type(s.algorithm_type), s.algorithm_type == SegAlgorithmType::kManual ? "" : s.algorithm_name.c_str());
  std::unique_ptr<DcmSegment> segment(raw);
  if (c.bad() || !segment) return invalid_argument("segment '" + s.label + "' was refused (" + c.text() + ")");
  if (s.display_rgb) {
    double l = 0, a = 0, b = 0;
    const auto& rgb = *s.display_rgb;
    IODCIELabUtil::rgb2DicomLab(l, a, b, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
    c = segment->setRecommendedDisplayCIELabValue(
        static_cast<Uint16>(std::lround(l)), static_cast<Uint16>(std::lround(a)), static_cast<Uint16>(std::lround(b)));
    if (c.bad()) return seg_export_error("colour of segment '" + s.label + "'", c);
  }
  Uint16 number = 0;
  c = seg.addSegment(segment.get(), number);
  if (c.bad()) return seg_export_error("adding segment '" + s.label + "'", c);
  segment.release();  // owned by seg now
  return ok_status();
}

// Referenced Series Sequence (Common Instance Reference module): the slices frames derive from.
Status add_references(DcmSegmentation& seg, const SegSource& src, const std::vector<std::vector<int64_t>>& slices) {
  std::vector<bool> used(src.slice_sop_instance_uids.size(), false);
  for (const auto& ks : slices)
    for (int64_t k : ks) used[static_cast<size_t>(k)] = true;
  IODReferences refs;
  size_t count = 0;
  for (size_t k = 0; k < used.size(); ++k) {
    if (!used[k]) continue;
    ++count;
    if (!refs.add(new IODImageReference(src.patient_id.c_str(), src.study_uid.c_str(), src.series_uid.c_str(),
                                        src.slice_sop_instance_uids[k].c_str(), src.sop_class_uid.c_str())))
      return internal_error("DICOM SEG: reference to slice " + std::to_string(k) + " was refused");
  }
  const size_t added = seg.getCommonInstanceReference().addReferences(refs, src.study_uid.c_str());
  if (added != count)
    return internal_error("DICOM SEG: " + std::to_string(added) + " of " + std::to_string(count) +
                          " slice references were written");
  return ok_status();
}

}  // namespace soiq::dicom
