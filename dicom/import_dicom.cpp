#include "dicom/import_dicom.h"

#include "dicom/import_seg.h"
#include "dicom/read_rt_struct.h"
#include "dicom/referenced_series.h"
#include "dicom/scan_dicom.h"

namespace soiq::dicom {
namespace {

constexpr char kSegmentationStorageUid[] = "1.2.840.10008.5.1.4.1.1.66.4";

}  // namespace

bool is_volume_modality(const std::string& m) { return m == "CT" || m == "MR" || m == "PT"; }

const SeriesImage* DicomImport::find_image(const std::string& uid) const {
  for (const auto& i : images)
    if (i.series_uid == uid) return &i;
  return nullptr;
}

Result<DicomImport> import_dicom(const std::vector<std::string>& paths, int64_t max_voxels) {
  DicomImport out;
  SOIQ_ASSIGN_OR_RETURN(out.scan, scan_dicom(paths));
  out.problems = out.scan.unreadable;
  for (const DicomSeries& series : out.scan.series) {
    if (!is_volume_modality(series.modality)) continue;
    auto image = read_image_series(series, max_voxels);
    if (!image.ok()) {
      out.problems.push_back({series.series_uid, Status(image.status().code(), "series " + series.series_uid + ": " +
                                                                                   image.status().message())});
      continue;
    }
    out.images.push_back(std::move(image).value());
  }
  for (const DicomSeries& series : out.scan.series) {
    if (series.modality != "RTSTRUCT") continue;
    for (const DicomInstance& inst : series.instances) {
      auto rs = read_rt_struct(inst.path);
      if (!rs.ok()) {
        out.problems.push_back({inst.path, rs.status()});
        continue;
      }
      auto ref = referenced_series(*rs, out.scan);
      if (!ref.ok()) {
        out.problems.push_back({inst.path, ref.status()});
        continue;
      }
      const SeriesImage* image = out.find_image(*ref);
      if (image == nullptr) {
        out.problems.push_back({inst.path, not_found("RT Structure Set '" + inst.path + "': its image series " + *ref +
                                                     " could not be imported (see the problem reported for it)")});
        continue;
      }
      auto converted = convert_rt_struct(*rs, image->image.geometry, max_voxels);
      if (!converted.ok()) {
        out.problems.push_back({inst.path, converted.status()});
        continue;
      }
      ImportedStructureSet set{
          rs->path, rs->sop_instance_uid,        rs->series_uid, rs->study_uid, rs->patient_id, rs->label,
          *ref,     std::move(converted).value()};
      out.structure_sets.push_back(std::move(set));
    }
  }
  for (const DicomSeries& series : out.scan.series) {
    for (const DicomInstance& inst : series.instances) {
      if (inst.sop_class_uid != kSegmentationStorageUid) continue;
      auto seg = import_seg(inst, out.scan, out.images);
      if (!seg.ok()) {
        out.problems.push_back({inst.path, seg.status()});
        continue;
      }
      out.structure_sets.push_back(std::move(seg).value());
    }
  }
  return out;
}

}  // namespace soiq::dicom
