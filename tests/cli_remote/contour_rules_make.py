#!/usr/bin/env python3
"""Writes two RT Structure Sets on STS_002's CT from its own (tests/data/sts/STS_002/dicom/CT/mask/RS.dcm),
with pydicom, to test soiq's contour rules end to end:

  three_rois.dcm   the GTV three times: 'sound A'; 'strayed', one point of its first contour moved
                   2 mm along the slice normal (not planar); 'sound B' with every contour moved 0.3
                   of the slice spacing off its plane (still nearest its own slice)
  between.dcm      the GTV once, every contour midway between two slices (no nearest slice)

usage: contour_rules_make.py SOURCE_RS OUT_DIR SLICE_SPACING_MM"""
import copy
import sys

import pydicom
from pydicom.uid import generate_uid


def moved(contour, dz, first_point_only=False):
    c = copy.deepcopy(contour)
    data = [float(v) for v in c.ContourData]
    for p in range(0, len(data), 3):
        if first_point_only and p > 0:
            break
        data[p + 2] += dz
    c.ContourData = ["%.6f" % v for v in data]
    return c


def structure_set(source, rois):
    """rois: (number, name, contour transform) per ROI, each a copy of the source's first ROI."""
    ds = copy.deepcopy(source)
    ds.SOPInstanceUID = generate_uid()
    ds.file_meta.MediaStorageSOPInstanceUID = ds.SOPInstanceUID
    ds.SeriesInstanceUID = generate_uid()
    first_roi = source.StructureSetROISequence[0]
    first_contours = source.ROIContourSequence[0]
    first_obs = source.RTROIObservationsSequence[0] if "RTROIObservationsSequence" in source else None
    ds.StructureSetROISequence = []
    ds.ROIContourSequence = []
    if first_obs is not None:
        ds.RTROIObservationsSequence = []
    for number, name, transform in rois:
        roi = copy.deepcopy(first_roi)
        roi.ROINumber = number
        roi.ROIName = name
        ds.StructureSetROISequence.append(roi)
        contours = copy.deepcopy(first_contours)
        contours.ReferencedROINumber = number
        contours.ContourSequence = [transform(i, c) for i, c in enumerate(first_contours.ContourSequence)]
        ds.ROIContourSequence.append(contours)
        if first_obs is not None:
            obs = copy.deepcopy(first_obs)
            obs.ObservationNumber = number
            obs.ReferencedROINumber = number
            ds.RTROIObservationsSequence.append(obs)
    return ds


def main():
    source = pydicom.dcmread(sys.argv[1])
    out = sys.argv[2]
    spacing = float(sys.argv[3])
    three = structure_set(source, [
        (1, "sound A", lambda i, c: c),
        (2, "strayed", lambda i, c: moved(c, 2.0, first_point_only=True) if i == 0 else c),
        (3, "sound B", lambda i, c: moved(c, 0.3 * spacing)),
    ])
    three.save_as(out + "/three_rois.dcm")
    between = structure_set(source, [(1, "between", lambda i, c: moved(c, 0.5 * spacing))])
    between.save_as(out + "/between.dcm")


if __name__ == "__main__":
    main()
