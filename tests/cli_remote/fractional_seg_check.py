#!/usr/bin/env python3
"""Checks a FRACTIONAL DICOM SEG that `soiq export-seg --fractional` wrote against soiq's own
coverage fractions of the same structure on the same series (`soiq convert ID --series UID
--fractional -o X.nii`), with pydicom (Debian's python3-pydicom) and no numpy:

  fractional_seg_check.py SEG.dcm FRACTIONS.nii SERIES_DIR VOLUME_MM3 BINARY_SEG.dcm

- the SEG's header: FRACTIONAL, OCCUPANCY, Maximum Fractional Value 255, 8 bits in 8, high bit 7;
- every frame placed twice, by its Image Position (Patient) on the NIfTI's grid and by the slice
  its Referenced SOP Instance UID names among the files under SERIES_DIR, which must agree; its
  bytes equal the NIfTI's slice byte for byte; every slice with any coverage has a frame;
- the sum of fraction x voxel volume (the SEG's own Pixel Spacing and Spacing Between Slices)
  equals VOLUME_MM3 (the convert summary's, from unrounded fractions) within the bytes' rounding;
- BINARY_SEG (of the same structure) has other Series and SOP Instance UIDs.

Prints one line of figures; exits 1 with one line on any mismatch."""
import os
import struct
import sys

import pydicom
import pydicom.errors

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
from fraction_file import lps, read_nifti  # noqa: E402


def fail(message):
    sys.exit("fractional SEG: " + message)


def main():
    seg_path, nifti_path, series_dir, volume_mm3, binary_path = sys.argv[1:6]
    seg = pydicom.dcmread(seg_path)
    header = {
        "SOPClassUID": "1.2.840.10008.5.1.4.1.1.66.4",
        "SegmentationType": "FRACTIONAL",
        "SegmentationFractionalType": "OCCUPANCY",
        "MaximumFractionalValue": 255,
        "BitsAllocated": 8,
        "BitsStored": 8,
        "HighBit": 7,
        "SamplesPerPixel": 1,
        "PixelRepresentation": 0,
    }
    for keyword, want in header.items():
        if seg.get(keyword) != want:
            fail("%s is %r, not %r" % (keyword, seg.get(keyword), want))

    (nx, ny, nz), srow, kind, _, raw = read_nifti(nifti_path)
    if kind != "uint8":
        fail("%s holds %s fractions, not uint8" % (nifti_path, kind))
    rows, columns, frames = int(seg.Rows), int(seg.Columns), int(seg.NumberOfFrames)
    if (columns, rows) != (nx, ny):
        fail("frames are %dx%d, the series' grid %dx%d" % (columns, rows, nx, ny))
    pixels = bytes(seg.PixelData)
    if len(pixels) < frames * rows * columns:
        fail("Pixel Data holds %d bytes for %d frames of %dx%d" % (len(pixels), frames, rows, columns))

    # The series' slices by SOP Instance UID, from the files soiq imported.
    slice_position = {}
    for folder, _, names in os.walk(series_dir):
        for name in names:
            try:
                ds = pydicom.dcmread(os.path.join(folder, name), stop_before_pixels=True)
            except pydicom.errors.InvalidDicomError:
                continue
            if ds.get("SeriesInstanceUID") == seg.ReferencedSeriesSequence[0].SeriesInstanceUID:
                slice_position[ds.SOPInstanceUID] = [float(v) for v in ds.ImagePositionPatient]
    if len(slice_position) != nz:
        fail("%d slices of the referenced series in %s, the grid has %d" % (len(slice_position), series_dir, nz))
    origins = [lps(srow, 0, 0, k) for k in range(nz)]

    def slice_at(position):
        k = min(range(nz), key=lambda k: sum((a - b) ** 2 for a, b in zip(origins[k], position)))
        # float32 sform: within a micrometre of the slice's origin.
        if sum((a - b) ** 2 for a, b in zip(origins[k], position)) > 1e-6:
            fail("a frame at %s lies on no slice of the grid" % (position,))
        return k

    shared = seg.SharedFunctionalGroupsSequence[0]
    measures = shared.PixelMeasuresSequence[0]
    voxel_mm3 = float(measures.PixelSpacing[0]) * float(measures.PixelSpacing[1]) * float(
        measures.SpacingBetweenSlices)
    frame_bytes = rows * columns
    seen, differing, partial, total = set(), 0, 0, 0
    for f, group in enumerate(seg.PerFrameFunctionalGroupsSequence):
        k = slice_at([float(v) for v in group.PlanePositionSequence[0].ImagePositionPatient])
        ref = group.DerivationImageSequence[0].SourceImageSequence[0].ReferencedSOPInstanceUID
        if slice_at(slice_position.get(ref, [1e9, 1e9, 1e9])) != k:
            fail("frame %d is at slice %d but references another slice (%s)" % (f, k, ref))
        if int(group.SegmentIdentificationSequence[0].ReferencedSegmentNumber) != 1:
            fail("frame %d is not of segment 1" % f)
        if list(group.FrameContentSequence[0].DimensionIndexValues) != [1, k + 1]:
            fail("frame %d's dimension index values are %s" % (f, group.FrameContentSequence[0].DimensionIndexValues))
        if k in seen:
            fail("two frames of slice %d" % k)
        seen.add(k)
        frame = pixels[f * frame_bytes:(f + 1) * frame_bytes]
        want = bytes(raw[nx * ny * k:nx * ny * (k + 1)])  # NIfTI: i fastest, then j = SEG's rows and columns
        differing += sum(a != b for a, b in zip(frame, want))
        partial += sum(1 for b in frame if 0 < b < 255)
        total += sum(frame)
    covered = {k for k in range(nz) if any(raw[nx * ny * k:nx * ny * (k + 1)])}
    if covered != seen:
        fail("frames on slices %s, coverage on slices %s" % (sorted(seen), sorted(covered)))
    if differing:
        fail("%d bytes of %d frames differ from soiq convert --fractional" % (differing, frames))
    volume = total / 255.0 * voxel_mm3
    # Each partial byte is round(255 f): off by at most 1/510 of a voxel; the summary prints 0.1 mm3.
    bound = partial * voxel_mm3 / 510.0 + 0.05
    if abs(volume - float(volume_mm3)) > bound:
        fail("sum of fractions x voxel volume is %.3f mm3, the convert summary says %s (bound %.3f)" %
             (volume, volume_mm3, bound))

    binary = pydicom.dcmread(binary_path, stop_before_pixels=True)
    if binary.SegmentationType != "BINARY":
        fail("%s is not a binary SEG" % binary_path)
    if binary.SeriesInstanceUID == seg.SeriesInstanceUID or binary.SOPInstanceUID == seg.SOPInstanceUID:
        fail("the binary and the fractional SEG share a UID")
    print("%d frames, %d bytes compared, 0 differing, %d partial; %.3f mm3 by the SEG, %s by convert (bound %.3f)" %
          (frames, frames * frame_bytes, partial, volume, volume_mm3, bound))


if __name__ == "__main__":
    main()
