#include "dicom/import_dicom.h"

#include "dicom/import_seg.h"
#include "dicom/known_series_check.h"
#include "dicom/read_rt_struct.h"
#include "dicom/referenced_series.h"
#include "dicom/scan_dicom.h"

namespace soiq::dicom {
namespace {

constexpr char kSegmentationStorageUid[] = "1.2.840.10008.5.1.4.1.1.66.4";

// One RT Structure Set on the grid of the series it references: among the files, else held by
// the caller (`known`, by the series uids the file names).
Result<ImportedStructureSet> import_rt_struct(const DicomInstance& inst, const DicomImport& in, int64_t max_voxels,
                                              const FindKnownSeries& known) {
  SOIQ_ASSIGN_OR_RETURN(RtStructureSet rs, read_rt_struct(inst.path));
  Result<std::string> ref = referenced_series(rs, in.scan);
  const ImageGeometry* grid = nullptr;
  std::optional<KnownSeries> held;
  if (ref.ok()) {
    const SeriesImage* image = in.find_image(*ref);
    if (image == nullptr)
      return not_found("RT Structure Set '" + inst.path + "': its image series " + *ref +
                       " could not be imported (see the problem reported for it)");
    grid = &image->image.geometry;
  } else {
    for (const std::string& uid : rs.referenced_series_uids) {
      if (known) held = known(uid);
      if (held) break;
    }
    if (!held) return ref.status();
    SOIQ_RETURN_IF_ERROR(check_same_patient_and_frame("RT Structure Set '" + inst.path + "'", rs.patient_id,
                                                      rs.frame_of_reference_uids, *held));
    ref = held->series_uid;
    grid = &held->geometry;
  }
  SOIQ_ASSIGN_OR_RETURN(ConvertedStructureSet converted, convert_rt_struct(rs, *grid, max_voxels));
  ImportedStructureSet set{rs.path, rs.sop_instance_uid,  rs.series_uid, rs.study_uid,    rs.patient_id, rs.label,
                           *ref,    std::move(converted), false,         held.has_value()};
  return set;
}

}  // namespace

bool is_volume_modality(const std::string& m) { return m == "CT" || m == "MR" || m == "PT"; }

const SeriesImage* DicomImport::find_image(const std::string& uid) const {
  for (const auto& i : images)
    if (i.series_uid == uid) return &i;
  return nullptr;
}

Result<DicomImport> import_dicom(const std::vector<std::string>& paths, int64_t max_voxels,
                                 const FindKnownSeries& known, const BeforeDecoding& before_decoding) {
  DicomImport out;
  SOIQ_ASSIGN_OR_RETURN(out.scan, scan_dicom(paths));
  if (before_decoding) SOIQ_RETURN_IF_ERROR(before_decoding(out.scan));
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
      auto set = import_rt_struct(inst, out, max_voxels, known);
      if (!set.ok()) {
        out.problems.push_back({inst.path, set.status()});
        out.failed_structure_sets.push_back(inst.path);
        continue;
      }
      out.structure_sets.push_back(std::move(set).value());
    }
  }
  for (const DicomSeries& series : out.scan.series) {
    for (const DicomInstance& inst : series.instances) {
      if (inst.sop_class_uid != kSegmentationStorageUid) continue;
      auto seg = import_seg(inst, out.scan, out.images, known);
      if (!seg.ok()) {
        out.problems.push_back({inst.path, seg.status()});
        out.failed_structure_sets.push_back(inst.path);
        continue;
      }
      out.structure_sets.push_back(std::move(seg).value());
    }
  }
  return out;
}

}  // namespace soiq::dicom
