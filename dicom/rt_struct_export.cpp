#include "dicom/rt_struct_export.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "dicom/dcmtk_file.h"
#include "dicom/dicom_value_fits.h"

namespace soiq::dicom {
namespace rt_struct_writing {

// The SOP class PS3.3 C.8.8.5 names for the RT Referenced Study Sequence's study reference (a
// retired class, still the value the standard's RT objects and their readers use).
constexpr const char* kStudyReferenceClass = "1.2.840.10008.3.1.2.3.1";

bool beyond_ascii(const std::string& v) {
  return std::any_of(v.begin(), v.end(), [](char ch) { return static_cast<unsigned char>(ch) >= 0x80; });
}

Status validate(const SegSource& source, const std::vector<RtStructRoi>& rois, const RtStructWriteOptions& options) {
  const ImageGeometry& g = source.geometry;
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  if (static_cast<int64_t>(source.slice_sop_instance_uids.size()) != g.dims[2])
    return invalid_argument("source series has " + std::to_string(source.slice_sop_instance_uids.size()) +
                            " slice SOP instance uids but its grid has " + std::to_string(g.dims[2]) + " slices");
  for (size_t k = 0; k < source.slice_sop_instance_uids.size(); ++k)
    if (source.slice_sop_instance_uids[k].empty())
      return invalid_argument("source series: slice " + std::to_string(k) + " has no SOP instance uid");
  const std::pair<const char*, const std::string*> required[] = {
      {"study uid", &source.study_uid},
      {"series uid", &source.series_uid},
      {"frame of reference uid", &source.frame_of_reference_uid},
      {"SOP class uid", &source.sop_class_uid}};
  for (const auto& [what, value] : required)
    if (value->empty()) return invalid_argument(std::string("source series has no ") + what);
  if (rois.empty()) return invalid_argument("no ROIs to write");
  int64_t points = 0;
  for (size_t r = 0; r < rois.size(); ++r) {
    const RtStructRoi& roi = rois[r];
    const std::string name = "ROI " + std::to_string(r + 1) + " ('" + roi.name + "')";
    if (roi.name.empty() || !fits_long_string(roi.name))
      return invalid_argument(name +
                              ": an ROI Name must be 1 to 64 characters without backslash or control characters");
    if (roi.generation_algorithm != "AUTOMATIC" && roi.generation_algorithm != "SEMIAUTOMATIC" &&
        roi.generation_algorithm != "MANUAL")
      return invalid_argument(name + ": ROI Generation Algorithm '" + roi.generation_algorithm +
                              "' is not AUTOMATIC, SEMIAUTOMATIC or MANUAL");
    if (!fits_short_string(roi.interpreted_type))
      return invalid_argument(name + ": RT ROI Interpreted Type '" + roi.interpreted_type + "' is not a CS value");
    if (roi.contours.empty())
      return failed_precondition("structure '" + roi.name + "' meets no slice plane of series " + source.series_uid +
                                 " (it lies between two planes or outside the grid), so it has no planar contour "
                                 "to write; export it as a SEG instead");
    for (size_t c = 0; c < roi.contours.size(); ++c) {
      const SliceSection& s = roi.contours[c];
      if (s.slice < 0 || s.slice >= g.dims[2])
        return invalid_argument(name + ": contour " + std::to_string(c + 1) + " is on slice " +
                                std::to_string(s.slice) + ", outside the series' " + std::to_string(g.dims[2]));
      if (s.points_mm.size() < 3)
        return invalid_argument(name + ": contour " + std::to_string(c + 1) + " has fewer than 3 points");
      for (const Vec3& p : s.points_mm)
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
          return invalid_argument(name + ": contour " + std::to_string(c + 1) + " has a non-finite point");
      points += static_cast<int64_t>(s.points_mm.size());
    }
  }
  if (points > options.max_points)
    return resource_exhausted("the RT Structure Set would hold " + std::to_string(points) + " contour points, over " +
                              std::to_string(options.max_points) + "; export fewer structures at once");
  return ok_status();
}

std::string new_uid(const char* root) {
  char buf[100];
  dcmGenerateUniqueIdentifier(buf, root);
  return buf;
}

// Collects the first failure of a chain of DCMTK puts, naming what was being written.
class Puts {
 public:
  void put(DcmItem& item, const DcmTagKey& tag, const std::string& value) {
    if (cond_.good()) {
      cond_ = item.putAndInsertString(tag, value.c_str());
      if (cond_.bad()) what_ = DcmTag(tag).getTagName();
    }
  }
  // A new item appended to sequence `tag` of `item`; nullptr once a put failed.
  DcmItem* add_item(DcmItem& item, const DcmTagKey& tag) {
    DcmItem* out = nullptr;
    if (cond_.good()) {
      cond_ = item.findOrCreateSequenceItem(tag, out, -2);
      if (cond_.bad()) what_ = DcmTag(tag).getTagName();
    }
    return cond_.good() ? out : nullptr;
  }
  Status status() const {
    if (cond_.good()) return ok_status();
    return internal_error("DICOM RT Structure Set: writing " + what_ + " was refused (" + cond_.text() + ")");
  }

 private:
  OFCondition cond_ = EC_Normal;
  std::string what_;
};

void put_identity(Puts& w, DcmItem& ds, const SegSource& src, const RtStructWriteOptions& options,
                  const WrittenRtStruct& out, const std::string& date, const std::string& time) {
  w.put(ds, DCM_SOPClassUID, UID_RTStructureSetStorage);
  w.put(ds, DCM_SOPInstanceUID, out.sop_instance_uid);
  w.put(ds, DCM_InstanceCreationDate, date);
  w.put(ds, DCM_InstanceCreationTime, time);
  w.put(ds, DCM_PatientName, src.patient_name);  // "" unless soiqd keeps names
  w.put(ds, DCM_PatientID, src.patient_id);
  w.put(ds, DCM_PatientBirthDate, type2_value(src.patient_birth_date, fits_date(src.patient_birth_date)));
  w.put(ds, DCM_PatientSex,
        src.patient_sex == "M" || src.patient_sex == "F" || src.patient_sex == "O" ? src.patient_sex : "");
  w.put(ds, DCM_StudyInstanceUID, src.study_uid);
  w.put(ds, DCM_StudyDate, type2_value(src.study_date, fits_date(src.study_date)));
  w.put(ds, DCM_StudyTime, type2_value(src.study_time, fits_time(src.study_time)));
  w.put(ds, DCM_ReferringPhysicianName, "");
  w.put(ds, DCM_StudyID, type2_value(src.study_id, fits_short_string(src.study_id)));
  w.put(ds, DCM_AccessionNumber, type2_value(src.accession_number, fits_short_string(src.accession_number)));
  w.put(ds, DCM_FrameOfReferenceUID, src.frame_of_reference_uid);
  w.put(ds, DCM_PositionReferenceIndicator, "");
  w.put(ds, DCM_Modality, "RTSTRUCT");
  w.put(ds, DCM_SeriesInstanceUID, out.series_uid);
  w.put(ds, DCM_SeriesNumber, std::to_string(options.series_number));
  w.put(ds, DCM_SeriesDescription, options.series_description);
  w.put(ds, DCM_OperatorsName, "");
  w.put(ds, DCM_Manufacturer, "soiq");
  w.put(ds, DCM_InstanceNumber, "1");
  w.put(ds, DCM_StructureSetLabel, options.label);
  w.put(ds, DCM_StructureSetDate, date);
  w.put(ds, DCM_StructureSetTime, time);
}

// Referenced Frame of Reference -> RT Referenced Study -> RT Referenced Series -> every slice.
void put_references(Puts& w, DcmItem& ds, const SegSource& src) {
  DcmItem* frame = w.add_item(ds, DCM_ReferencedFrameOfReferenceSequence);
  if (frame == nullptr) return;
  w.put(*frame, DCM_FrameOfReferenceUID, src.frame_of_reference_uid);
  DcmItem* study = w.add_item(*frame, DCM_RTReferencedStudySequence);
  if (study == nullptr) return;
  w.put(*study, DCM_ReferencedSOPClassUID, kStudyReferenceClass);
  w.put(*study, DCM_ReferencedSOPInstanceUID, src.study_uid);
  DcmItem* series = w.add_item(*study, DCM_RTReferencedSeriesSequence);
  if (series == nullptr) return;
  w.put(*series, DCM_SeriesInstanceUID, src.series_uid);
  for (const std::string& uid : src.slice_sop_instance_uids) {
    DcmItem* image = w.add_item(*series, DCM_ContourImageSequence);
    if (image == nullptr) return;
    w.put(*image, DCM_ReferencedSOPClassUID, src.sop_class_uid);
    w.put(*image, DCM_ReferencedSOPInstanceUID, uid);
  }
}

std::string contour_data(const std::vector<Vec3>& points) {
  std::string out;
  out.reserve(points.size() * 3 * 14);
  for (const Vec3& p : points)
    for (double c : p) {
      if (!out.empty()) out += '\\';
      out += format_ds(c);
    }
  return out;
}

void put_roi(Puts& w, DcmItem& ds, const SegSource& src, const RtStructRoi& roi, int number, WrittenRtStruct& out) {
  const std::string n = std::to_string(number);
  if (DcmItem* item = w.add_item(ds, DCM_StructureSetROISequence)) {
    w.put(*item, DCM_ROINumber, n);
    w.put(*item, DCM_ReferencedFrameOfReferenceUID, src.frame_of_reference_uid);
    w.put(*item, DCM_ROIName, roi.name);
    w.put(*item, DCM_ROIGenerationAlgorithm, roi.generation_algorithm);
  }
  if (DcmItem* item = w.add_item(ds, DCM_ROIContourSequence)) {
    const auto& c = roi.display_rgb;
    w.put(*item, DCM_ROIDisplayColor, std::to_string(c[0]) + "\\" + std::to_string(c[1]) + "\\" + std::to_string(c[2]));
    int contour_number = 0;
    for (const SliceSection& s : roi.contours) {
      DcmItem* contour = w.add_item(*item, DCM_ContourSequence);
      if (contour == nullptr) return;
      if (DcmItem* image = w.add_item(*contour, DCM_ContourImageSequence)) {
        w.put(*image, DCM_ReferencedSOPClassUID, src.sop_class_uid);
        w.put(*image, DCM_ReferencedSOPInstanceUID, src.slice_sop_instance_uids[static_cast<size_t>(s.slice)]);
      }
      w.put(*contour, DCM_ContourGeometricType, "CLOSED_PLANAR");
      w.put(*contour, DCM_NumberOfContourPoints, std::to_string(s.points_mm.size()));
      w.put(*contour, DCM_ContourNumber, std::to_string(++contour_number));
      w.put(*contour, DCM_ContourData, contour_data(s.points_mm));
      ++out.contour_count;
      out.point_count += static_cast<int64_t>(s.points_mm.size());
    }
    w.put(*item, DCM_ReferencedROINumber, n);
  }
  if (DcmItem* item = w.add_item(ds, DCM_RTROIObservationsSequence)) {
    w.put(*item, DCM_ObservationNumber, n);
    w.put(*item, DCM_ReferencedROINumber, n);
    w.put(*item, DCM_RTROIInterpretedType, roi.interpreted_type);
    w.put(*item, DCM_ROIInterpreter, "");
  }
}

}  // namespace rt_struct_writing

std::string format_ds(double value) {
  // The shortest precision that reads back exactly, as long as it fits; else the longest that fits.
  char buf[40];
  std::string fitting;
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, value);
    const std::string s = buf;
    if (s.size() > 16) break;
    fitting = s;
    if (std::strtod(buf, nullptr) == value) break;
  }
  return fitting;
}

Result<WrittenRtStruct> write_rt_struct(const SegSource& source, const std::vector<RtStructRoi>& rois,
                                        const RtStructWriteOptions& options) {
  namespace w = rt_struct_writing;
  SOIQ_RETURN_IF_ERROR(w::validate(source, rois, options));
  WrittenRtStruct out;
  out.series_uid = options.series_uid.empty() ? w::new_uid(SITE_SERIES_UID_ROOT) : options.series_uid;
  out.sop_instance_uid =
      options.sop_instance_uid.empty() ? w::new_uid(SITE_INSTANCE_UID_ROOT) : options.sop_instance_uid;
  OFString now_date, now_time;
  DcmDate::getCurrentDate(now_date);
  DcmTime::getCurrentTime(now_time, OFFalse /*seconds*/);
  const std::string date = options.date.empty() ? now_date.c_str() : options.date;
  const std::string time = options.time.empty() ? now_time.c_str() : options.time;

  DcmFileFormat file;
  DcmDataset& ds = *file.getDataset();
  w::Puts puts;
  // A patient's name, ROI name or description beyond ASCII is UTF-8 (the store keeps text so):
  // declared, or readers would take its bytes for ISO 646.
  bool utf8 = w::beyond_ascii(source.patient_name) || w::beyond_ascii(options.series_description);
  for (const RtStructRoi& r : rois) utf8 = utf8 || w::beyond_ascii(r.name);
  if (utf8) puts.put(ds, DCM_SpecificCharacterSet, "ISO_IR 192");
  w::put_identity(puts, ds, source, options, out, date, time);
  w::put_references(puts, ds, source);
  for (size_t r = 0; r < rois.size(); ++r) w::put_roi(puts, ds, source, rois[r], static_cast<int>(r + 1), out);
  SOIQ_RETURN_IF_ERROR(puts.status());
  Result<std::string> bytes = part10_bytes(file);
  if (!bytes.ok()) return Status(bytes.status().code(), "DICOM RT Structure Set: " + bytes.status().message());
  out.bytes = std::move(*bytes);
  return out;
}

}  // namespace soiq::dicom
