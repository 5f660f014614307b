#!/usr/bin/env python3
"""Judges the RT Structure Set of a structure that soiqd serves by DICOMweb against the SEG of the
same structure, as a client received both: pydicom reads each; the RT Structure Set is of its SOP
class with one ROI of the structure's name, and its contours, filled even-odd on the CT's own slices
by tests/dicom/rt_struct_even_odd_fill.py (which shares no code with soiq), are exactly the SEG's
voxels. Prints the ROI's name, its contour count and its voxel count.

usage: rt_struct_matches_seg.py RTSTRUCT SEG CT_DIR ROI_NAME
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
import pydicom

rt_path, seg_path, ct_dir, roi_name = sys.argv[1:5]
here = os.path.dirname(os.path.abspath(__file__))

rt = pydicom.dcmread(rt_path)
assert rt.Modality == "RTSTRUCT", rt.Modality
assert rt.SOPClassUID == "1.2.840.10008.5.1.4.1.1.481.3", rt.SOPClassUID
names = [r.ROIName for r in rt.StructureSetROISequence]
assert names == [roi_name], names

# The CT's slices in the order the fill stacks them: along the normal of their planes.
slices = []
for name in sorted(os.listdir(ct_dir)):
    f = pydicom.dcmread(os.path.join(ct_dir, name), stop_before_pixels=True)
    if "ImagePositionPatient" in f:
        slices.append(f)
o = np.array([float(v) for v in slices[0].ImageOrientationPatient])
normal = np.cross(o[:3], o[3:])
heights = np.array(sorted(float(np.array([float(v) for v in f.ImagePositionPatient]) @ normal) for f in slices))
nx, ny, nz = int(slices[0].Columns), int(slices[0].Rows), len(slices)

with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "rt.u8")
    printed = subprocess.run([sys.executable, os.path.join(here, "..", "dicom", "rt_struct_even_odd_fill.py"), rt_path,
                              "--series", ct_dir, out], check=True, capture_output=True, text=True).stdout.split()
    filled = np.fromfile(out, np.uint8).reshape(nz, ny, nx)
contours = int(printed[-2])

seg = pydicom.dcmread(seg_path)
assert seg.Modality == "SEG", seg.Modality
frames = seg.pixel_array.reshape(-1, ny, nx)
voxels = np.zeros((nz, ny, nx), np.uint8)
for f, item in enumerate(seg.PerFrameFunctionalGroupsSequence):
    h = float(np.array([float(v) for v in item.PlanePositionSequence[0].ImagePositionPatient]) @ normal)
    k = int(np.argmin(np.abs(heights - h)))
    assert abs(heights[k] - h) < 1e-3, f"SEG frame {f + 1} is on no CT slice"
    voxels[k] |= frames[f].astype(np.uint8)

differing = int(np.count_nonzero(filled != voxels))
assert contours > 0 and voxels.sum() > 0, (contours, int(voxels.sum()))
assert differing == 0, f"{differing} voxels differ between the RT Structure Set's contours and the SEG"
print(roi_name, contours, int(voxels.sum()))
