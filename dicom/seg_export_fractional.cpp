#include "dicom/seg_export_fractional.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmseg/segdoc.h>

#include <algorithm>
#include <memory>

#include "dicom/seg_export_steps.h"

namespace soiq::dicom {
namespace fractional_seg {

bool well_formed(const CoverageVolume& v) {
  const size_t lines = static_cast<size_t>(v.line_count()) + 1;
  return v.full_start.size() == lines && v.partial_start.size() == lines;
}

// The slices k with any coverage, ascending: the frames of the segment.
std::vector<int64_t> covered_slices(const CoverageVolume& v) {
  std::vector<int64_t> out;
  const int64_t ny = v.geometry.dims[1];
  for (int64_t k = 0; k < v.geometry.dims[2]; ++k) {
    const size_t first = static_cast<size_t>(ny * k), end = static_cast<size_t>(ny * (k + 1));
    if (v.full_start[end] > v.full_start[first] || v.partial_start[end] > v.partial_start[first]) out.push_back(k);
  }
  return out;
}

// Slice k's bytes (row-major: rows = j, columns = i) as to_fraction_bytes gives them, without the
// dense volume.
void fill_fraction_slice(const CoverageVolume& v, int64_t k, std::vector<Uint8>& frame) {
  const int64_t nx = v.geometry.dims[0], ny = v.geometry.dims[1];
  std::fill(frame.begin(), frame.end(), Uint8{0});
  for (int64_t j = 0; j < ny; ++j) {
    const size_t line = static_cast<size_t>(j + ny * k);
    Uint8* row = frame.data() + j * nx;
    for (int64_t r = v.full_start[line]; r < v.full_start[line + 1]; ++r) {
      const Run& run = v.full[static_cast<size_t>(r)];
      std::fill(row + run.begin, row + run.end, Uint8{kSegMaxFractionalValue});
    }
    for (int64_t p = v.partial_start[line]; p < v.partial_start[line + 1]; ++p) {
      const PartialVoxel& pv = v.partial[static_cast<size_t>(p)];
      row[pv.i] = fraction_byte(pv.fraction);
    }
  }
}

Status check(const SegSource& source, const std::vector<FractionalSegSegment>& segments, const SegWriteOptions& options,
             std::vector<std::vector<int64_t>>& slices_of_segment) {
  SOIQ_RETURN_IF_ERROR(check_seg_source(source));
  if (segments.empty()) return invalid_argument("no segments to write");
  if (segments.size() > 65535) return invalid_argument("a SEG holds at most 65535 segments");
  int64_t frames = 0;
  slices_of_segment.clear();
  for (size_t s = 0; s < segments.size(); ++s) {
    const FractionalSegSegment& seg = segments[s];
    SOIQ_RETURN_IF_ERROR(check_segment(seg, s + 1, seg.coverage.geometry, source.geometry));
    if (!well_formed(seg.coverage))
      return invalid_argument("segment " + std::to_string(s + 1) + " ('" + seg.label +
                              "'): malformed coverage volume (its index arrays do not have one entry per line + 1)");
    slices_of_segment.push_back(covered_slices(seg.coverage));
    if (slices_of_segment.back().empty()) return invalid_argument("structure '" + seg.label + "' has no voxels");
    frames += static_cast<int64_t>(slices_of_segment.back().size());
  }
  return check_seg_size(frames, frames * source.geometry.dims[0] * source.geometry.dims[1], options);
}

}  // namespace fractional_seg

// DCMTK 3.6.7's dcmseg, as its headers say and as its output shows: createFractionalSegmentation
// sets SegmentationFractionalType and Maximum Fractional Value and, when written, Bits Allocated =
// Bits Stored = 8, High Bit 7, and Pixel Data as the frames' bytes back to back (addFrame copies a
// fractional frame's bytes as they are). Unlike its binary frames (put_pixel_data), that layout is
// what PS3.5 asks, so its Pixel Data is kept.
Result<WrittenSeg> write_fractional_seg(const SegSource& source, const std::vector<FractionalSegSegment>& segments,
                                        const SegWriteOptions& options) {
  std::vector<std::vector<int64_t>> slices;
  SOIQ_RETURN_IF_ERROR(fractional_seg::check(source, segments, options, slices));
  quiet_dcmtk_seg_logs();
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<DcmSegmentation> seg, create_seg(source, options, kSegMaxFractionalValue));
  std::vector<const SegSegmentDescription*> described;
  for (const FractionalSegSegment& s : segments) described.push_back(&s);
  WrittenSeg out;
  SOIQ_RETURN_IF_ERROR(describe_seg(*seg, source, described, options, out));
  std::vector<Uint8> frame(static_cast<size_t>(source.geometry.dims[0] * source.geometry.dims[1]));
  for (size_t s = 0; s < segments.size(); ++s) {
    for (int64_t k : slices[s]) {
      fractional_seg::fill_fraction_slice(segments[s].coverage, k, frame);
      SOIQ_RETURN_IF_ERROR(add_frame(*seg, source, segments[s].label, static_cast<Uint16>(s + 1), k,
                                     "fraction of each voxel inside the structure", frame));
    }
  }
  SOIQ_RETURN_IF_ERROR(add_references(*seg, source, slices));
  SOIQ_RETURN_IF_ERROR(encode_seg(*seg, source, described, options, nullptr, out));
  return out;
}

int64_t fractional_seg_write_peak_bytes(const ImageGeometry& geometry,
                                        const std::vector<FractionalSegSegment>& segments) {
  int64_t frames = 0;
  for (const FractionalSegSegment& s : segments) {
    if (fractional_seg::well_formed(s.coverage))
      frames += static_cast<int64_t>(fractional_seg::covered_slices(s.coverage).size());
  }
  const int64_t frame_bytes = geometry.dims[0] * geometry.dims[1];
  return 3 * frames * frame_bytes + frame_bytes + frames * 4096 + (int64_t(1) << 20);
}

}  // namespace soiq::dicom
