#include "dicom/import_seg.h"

#include "dicom/dcmtk_file.h"
#include "dicom/known_series_check.h"
#include "dicom/read_seg.h"
#include "dicom/volume_surface.h"

namespace soiq::dicom {
namespace {

struct SegHeader {
  std::string sop_instance_uid, series_uid, study_uid, patient_id, frame_of_reference_uid, description;
  std::string referenced_series_uid;  // "" when the SEG has no Referenced Series Sequence
};

Result<SegHeader> read_header(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(auto file, load_dicom_file(path, /*until_pixel_data=*/true));
  DcmDataset& ds = *file->getDataset();
  SegHeader h{get_string(ds, DCM_SOPInstanceUID),
              get_string(ds, DCM_SeriesInstanceUID),
              get_string(ds, DCM_StudyInstanceUID),
              get_string(ds, DCM_PatientID),
              get_string(ds, DCM_FrameOfReferenceUID),
              get_string(ds, DCM_SeriesDescription),
              ""};
  DcmItem* series = nullptr;
  if (ds.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series, 0).good() && series)
    h.referenced_series_uid = get_string(*series, DCM_SeriesInstanceUID);
  return h;
}

// Without a Referenced Series Sequence: the one imported series of the study in its frame of reference.
Result<std::string> series_by_frame_of_reference(const SegHeader& h, const std::string& path, const DicomScan& scan,
                                                 const std::vector<SeriesImage>& images) {
  std::vector<std::string> candidates;
  for (const SeriesImage& image : images) {
    const DicomSeries* s = scan.find_series(image.series_uid);
    if (s && s->study_uid == h.study_uid && !h.frame_of_reference_uid.empty() &&
        s->frame_of_reference_uid == h.frame_of_reference_uid)
      candidates.push_back(image.series_uid);
  }
  if (candidates.size() == 1) return candidates.front();
  return not_found("SEG '" + path + "' has no Referenced Series Sequence and " + std::to_string(candidates.size()) +
                   " imported image series of its study share its frame of reference (1 is needed); import it "
                   "with the series it was drawn on");
}

}  // namespace

Result<ImportedStructureSet> import_seg(const DicomInstance& inst, const DicomScan& scan,
                                        const std::vector<SeriesImage>& images, const FindKnownSeries& known) {
  const std::string& path = inst.path;
  SOIQ_ASSIGN_OR_RETURN(const SegHeader h, read_header(path));
  std::string ref = h.referenced_series_uid;
  if (ref.empty()) {
    SOIQ_ASSIGN_OR_RETURN(ref, series_by_frame_of_reference(h, path, scan, images));
  }
  const SeriesImage* image = nullptr;
  for (const SeriesImage& i : images)
    if (i.series_uid == ref) image = &i;
  std::optional<KnownSeries> held;
  if (image == nullptr && known) held = known(ref);
  if (image == nullptr && !held)
    return not_found("SEG '" + path + "': its image series " + ref +
                     " is neither among the imported series nor stored (send it with the SEG, or see the problem "
                     "reported for it)");
  const DicomSeries* series = scan.find_series(ref);
  const std::string series_frame = held ? held->frame_of_reference_uid : series ? series->frame_of_reference_uid : "";
  if (!series_frame.empty() && !h.frame_of_reference_uid.empty() && series_frame != h.frame_of_reference_uid)
    return invalid_argument("SEG '" + path + "' is in frame of reference " + h.frame_of_reference_uid +
                            " but its series " + ref + " is in " + series_frame);
  if (held) SOIQ_RETURN_IF_ERROR(check_same_patient_and_frame("SEG '" + path + "'", h.patient_id, {}, *held));
  const ImageGeometry& grid = held ? held->geometry : image->image.geometry;
  SOIQ_ASSIGN_OR_RETURN(SegObject seg, read_seg_file(path, grid));

  ImportedStructureSet out{path, h.sop_instance_uid, h.series_uid, h.study_uid, h.patient_id, h.description, ref, {},
                           true, held.has_value()};
  for (ReadSegment& segment : seg.segments) {
    const std::string name =
        segment.label.empty() ? "segment " + std::to_string(segment.segment_number) : segment.label;
    if (voxel_count(segment.volume) == 0) {
      out.converted.skipped.push_back({segment.segment_number, name, "no voxels"});
      continue;
    }
    ImportedStructure s;
    s.roi_number = segment.segment_number;
    s.name = name;
    s.volume = std::move(segment.volume);
    SOIQ_ASSIGN_OR_RETURN(s.surface, volume_surface(s.volume));
    out.converted.structures.push_back(std::move(s));
  }
  return out;
}

}  // namespace soiq::dicom
