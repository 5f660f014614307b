// The frames write_seg adds: which slices of a segment become frames, the functional groups they
// share and those of each frame, and the Pixel Data that holds their bits.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgfracon.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmseg/segdoc.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>

#include "dicom/seg_export_steps.h"

namespace soiq::dicom {
namespace {

// A DS value (at most 16 characters, Part 5 6.2) with as many significant digits as fit: 16
// characters keep about 1e-11 mm of a position and 1e-13 of a direction cosine.
std::string frame_ds(double v) {
  if (v == 0) return "0";  // also turns -0 into 0
  char buf[64];
  for (int precision = 16; precision > 0; --precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strlen(buf) <= 16) return buf;
  }
  return "0";
}

// Unpacked frame of slice k (one byte per pixel, row-major: rows = j, columns = i), as
// DcmSegmentation::addFrame takes it.
void fill_slice(const RunLengthVolume& v, int64_t k, std::vector<Uint8>& frame) {
  const int64_t nx = v.geometry.dims[0], ny = v.geometry.dims[1];
  std::fill(frame.begin(), frame.end(), Uint8{0});
  for (int64_t j = 0; j < ny; ++j) {
    const int64_t line = j + ny * k;
    for (int64_t r = v.line_start[static_cast<size_t>(line)]; r < v.line_start[static_cast<size_t>(line + 1)]; ++r) {
      const Run& run = v.runs[static_cast<size_t>(r)];
      std::fill(frame.begin() + j * nx + run.begin, frame.begin() + j * nx + run.end, Uint8{1});
    }
  }
}

}  // namespace

std::vector<int64_t> occupied_slices(const RunLengthVolume& v) {
  std::vector<int64_t> out;
  const int64_t ny = v.geometry.dims[1];
  for (int64_t k = 0; k < v.geometry.dims[2]; ++k)
    if (v.line_start[static_cast<size_t>(ny * (k + 1))] > v.line_start[static_cast<size_t>(ny * k)]) out.push_back(k);
  return out;
}

// Plane Orientation and Pixel Measures are the same for every frame. The Multi-frame Dimension
// module (Type 1) indexes frames by (segment number, plane position), the usual SEG organisation.
Status add_shared_groups(DcmSegmentation& seg, const ImageGeometry& g, const std::string& organization_uid) {
  const Vec3 row{g.direction[0][0], g.direction[1][0], g.direction[2][0]};  // direction of increasing i
  const Vec3 col{g.direction[0][1], g.direction[1][1], g.direction[2][1]};  // direction of increasing j
  std::unique_ptr<FGPlaneOrientationPatient> orientation(FGPlaneOrientationPatient::createMinimal(
      frame_ds(row[0]).c_str(), frame_ds(row[1]).c_str(), frame_ds(row[2]).c_str(), frame_ds(col[0]).c_str(),
      frame_ds(col[1]).c_str(), frame_ds(col[2]).c_str()));
  if (!orientation) return internal_error("DICOM SEG: could not create the Plane Orientation group");
  OFCondition c = seg.addForAllFrames(*orientation);
  FGPixelMeasures measures;
  // Along the normal of the planes: on a tilted series the step from frame to frame is longer.
  const std::string slice = frame_ds(g.slice_distance_mm());
  if (c.good()) c = measures.setPixelSpacing((frame_ds(g.spacing_mm[1]) + "\\" + frame_ds(g.spacing_mm[0])).c_str());
  if (c.good()) c = measures.setSliceThickness(slice.c_str());
  // An unevenly spaced series has no one spacing (the attribute is optional): each frame's Image
  // Position (Patient) says where it is, and the thickness above is the mean step.
  if (c.good() && !g.uneven()) c = measures.setSpacingBetweenSlices(slice.c_str());
  if (c.good()) c = seg.addForAllFrames(measures);
  if (c.bad()) return seg_export_error("shared functional groups", c);
  const std::string organization = organization_uid.empty() ? new_uid(SITE_INSTANCE_UID_ROOT) : organization_uid;
  IODMultiframeDimensionModule& dims = seg.getDimensions();
  c = dims.addDimensionIndex(DCM_ReferencedSegmentNumber, organization.c_str(), DCM_SegmentIdentificationSequence,
                             "ReferencedSegmentNumber");
  if (c.good())
    c = dims.addDimensionIndex(DCM_ImagePositionPatient, organization.c_str(), DCM_PlanePositionSequence,
                               "ImagePositionPatient");
  if (c.bad()) return seg_export_error("dimension index", c);
  return ok_status();
}

Status add_frame(DcmSegmentation& seg, const SegSource& src, const std::string& label, Uint16 segment_number, int64_t k,
                 const char* derivation_text, std::vector<Uint8>& frame) {
  const ImageGeometry& g = src.geometry;
  const CodeSequenceMacro derivation("113076", "DCM", "Segmentation");
  const CodeSequenceMacro purpose("121322", "DCM", "Source image for image processing operation");
  const Vec3 p = g.index_to_physical({0, 0, static_cast<double>(k)});
  std::unique_ptr<FGPlanePosPatient> position(
      FGPlanePosPatient::createMinimal(frame_ds(p[0]).c_str(), frame_ds(p[1]).c_str(), frame_ds(p[2]).c_str()));
  FGFrameContent content;
  OFCondition c = content.setDimensionIndexValues(segment_number, 0);
  if (c.good()) c = content.setDimensionIndexValues(static_cast<Uint32>(k + 1), 1);
  ImageSOPInstanceReferenceMacro ref;
  if (c.good()) c = ref.setReferencedSOPClassUID(src.sop_class_uid.c_str(), OFFalse);
  if (c.good())
    c = ref.setReferencedSOPInstanceUID(src.slice_sop_instance_uids[static_cast<size_t>(k)].c_str(), OFFalse);
  if (c.bad()) return seg_export_error("frame of slice " + std::to_string(k) + " of '" + label + "'", c);
  OFVector<ImageSOPInstanceReferenceMacro> refs;
  refs.push_back(ref);
  std::unique_ptr<FGDerivationImage> derived(
      FGDerivationImage::createMinimal(refs, derivation_text, derivation, purpose));
  if (!position || !derived)
    return internal_error("DICOM SEG: could not create the groups of slice " + std::to_string(k) + " of '" + label +
                          "'");
  OFVector<FGBase*> groups;
  groups.push_back(position.get());
  groups.push_back(&content);
  groups.push_back(derived.get());
  c = seg.addFrame(frame.data(), segment_number, groups);  // copies the groups
  if (c.bad()) return seg_export_error("frame of slice " + std::to_string(k) + " of '" + label + "'", c);
  return ok_status();
}

Status add_frames(DcmSegmentation& seg, const SegSource& src, const SegSegment& s, Uint16 segment_number,
                  const std::vector<int64_t>& slices, BinaryFramePacker& pixels) {
  std::vector<Uint8> frame(static_cast<size_t>(src.geometry.dims[0] * src.geometry.dims[1]));
  for (int64_t k : slices) {
    fill_slice(s.volume, k, frame);
    pixels.add_frame(frame);  // first: addFrame may scribble on the buffer it packs (its pixels are replaced)
    SOIQ_RETURN_IF_ERROR(add_frame(seg, src, s.label, segment_number, k, "voxels inside the structure", frame));
  }
  return ok_status();
}

// DCMTK 3.6.7 starts every frame on a byte boundary, which PS3.5 8.1.1 / 8.2 do not allow when
// rows x columns is not a multiple of 8 (pydicom and other readers then shift every later frame):
// its Pixel Data is replaced by ours, the frames' bits back to back.
Status put_pixel_data(DcmDataset& ds, const BinaryFramePacker& pixels) {
  const std::vector<uint8_t> packed = pixels.bytes();
  const OFCondition c =
      ds.putAndInsertUint8Array(DCM_PixelData, packed.data(), static_cast<unsigned long>(packed.size()));
  if (c.bad()) return seg_export_error("setting the Pixel Data", c);
  return ok_status();
}

}  // namespace soiq::dicom
