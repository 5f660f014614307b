#include "dicom/read_rt_struct.h"

#include <algorithm>
#include <cstdlib>
#include <map>

#include "dicom/dcmtk_file.h"

namespace soiq::dicom {
namespace {

void add_unique(std::vector<std::string>& list, const std::string& value) {
  if (!value.empty() && std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

void add_contour_images(DcmItem& item, std::vector<std::string>& uids) {
  DcmItem* image = nullptr;
  for (long i = 0; item.findAndGetSequenceItem(DCM_ContourImageSequence, image, i).good(); ++i)
    add_unique(uids, get_string(*image, DCM_ReferencedSOPInstanceUID));
}

// Contour Data as numbers. The whole value is parsed once: asking DCMTK for each of thousands of
// values by position re-splits the string every time.
Result<std::vector<double>> contour_numbers(DcmItem& contour, const std::string& where) {
  const std::string text = get_string_array(contour, DCM_ContourData);
  std::vector<double> v;
  const char* p = text.c_str();
  while (*p != '\0') {
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    if (end == p) return invalid_argument(where + ": Contour Data holds a value that is not a number");
    v.push_back(x);
    p = end;
    while (*p == ' ') ++p;
    if (*p == '\\') ++p;
  }
  if (v.size() % 3 != 0)
    return invalid_argument(where + ": Contour Data has " + std::to_string(v.size()) + " numbers, not a multiple of 3");
  return v;
}

}  // namespace

Result<RtStructureSet> read_rt_struct(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(auto file, load_dicom_file(path, /*until_pixel_data=*/false));
  DcmDataset& ds = *file->getDataset();
  RtStructureSet rs;
  rs.path = path;
  const std::string modality = get_string(ds, DCM_Modality);
  if (modality != "RTSTRUCT")
    return invalid_argument("'" + path + "' is not an RT Structure Set (Modality '" + modality + "')");
  rs.sop_instance_uid = get_string(ds, DCM_SOPInstanceUID);
  rs.series_uid = get_string(ds, DCM_SeriesInstanceUID);
  rs.study_uid = get_string(ds, DCM_StudyInstanceUID);
  rs.patient_id = get_string(ds, DCM_PatientID);
  rs.label = get_string(ds, DCM_StructureSetLabel);

  DcmItem* frame = nullptr;
  for (long f = 0; ds.findAndGetSequenceItem(DCM_ReferencedFrameOfReferenceSequence, frame, f).good(); ++f) {
    add_unique(rs.frame_of_reference_uids, get_string(*frame, DCM_FrameOfReferenceUID));
    DcmItem* study = nullptr;
    for (long s = 0; frame->findAndGetSequenceItem(DCM_RTReferencedStudySequence, study, s).good(); ++s) {
      DcmItem* series = nullptr;
      for (long r = 0; study->findAndGetSequenceItem(DCM_RTReferencedSeriesSequence, series, r).good(); ++r) {
        add_unique(rs.referenced_series_uids, get_string(*series, DCM_SeriesInstanceUID));
        add_contour_images(*series, rs.referenced_image_uids);
      }
    }
  }

  std::map<int64_t, size_t> roi_by_number;
  DcmItem* item = nullptr;
  for (long i = 0; ds.findAndGetSequenceItem(DCM_StructureSetROISequence, item, i).good(); ++i) {
    RtRoi roi;
    roi.number = static_cast<int64_t>(get_number(*item, DCM_ROINumber).value_or(0));
    roi.name = get_string(*item, DCM_ROIName);
    roi.frame_of_reference_uid = get_string(*item, DCM_ReferencedFrameOfReferenceUID);
    roi_by_number[roi.number] = rs.rois.size();
    rs.rois.push_back(std::move(roi));
  }

  for (long i = 0; ds.findAndGetSequenceItem(DCM_ROIContourSequence, item, i).good(); ++i) {
    const auto number = static_cast<int64_t>(get_number(*item, DCM_ReferencedROINumber).value_or(0));
    auto it = roi_by_number.find(number);
    if (it == roi_by_number.end()) {  // contours of an ROI the structure set does not declare
      RtRoi roi;
      roi.number = number;
      it = roi_by_number.emplace(number, rs.rois.size()).first;
      rs.rois.push_back(std::move(roi));
    }
    RtRoi& roi = rs.rois[it->second];
    DcmItem* contour = nullptr;
    for (long c = 0; item->findAndGetSequenceItem(DCM_ContourSequence, contour, c).good(); ++c) {
      add_contour_images(*contour, rs.referenced_image_uids);
      const std::string type = get_string(*contour, DCM_ContourGeometricType);
      if (type != "CLOSED_PLANAR") {
        ++roi.other_contours;
        if (roi.other_types.find(type) == std::string::npos)
          roi.other_types += (roi.other_types.empty() ? "" : ", ") + (type.empty() ? std::string("(none)") : type);
        continue;
      }
      const std::string where =
          "'" + path + "' ROI " + std::to_string(roi.number) + " '" + roi.name + "' contour " + std::to_string(c);
      SOIQ_ASSIGN_OR_RETURN(std::vector<double> xyz, contour_numbers(*contour, where));
      PlanarContour pc;
      for (size_t p = 0; p + 2 < xyz.size(); p += 3) pc.points_mm.push_back({xyz[p], xyz[p + 1], xyz[p + 2]});
      roi.contours.push_back(std::move(pc));
    }
  }
  return rs;
}

}  // namespace soiq::dicom
