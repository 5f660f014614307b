#!/usr/bin/env python3
"""An independent reading of an RT Structure Set, for soiq's tests: pydicom parses the file and each
ROI's CLOSED_PLANAR contours are filled on a grid by the even-odd rule with the crossing-number
point-in-polygon test. A voxel centre is inside a contour iff a ray from it towards +i crosses an
odd number of the contour's edges, an edge end lying exactly on the ray's row counting as below
it ((y_a > y) != (y_b > y)), and a crossing exactly at the centre not being to its right; a voxel is inside the ROI iff it is inside an odd number of the ROI's contours on its
slice (PS3.3 C.8.8.6: holes and parts are separate contours). Shares no code with soiq.

usage: rt_struct_even_odd_fill.py RTSTRUCT GRID.json OUT.u8
GRID.json: {"origin": [x, y, z], "spacing": [si, sj, sk], "direction": [[...], [...], [...]]
            (rows; its columns are the unit directions of i, j, k in LPS), "dims": [nx, ny, nz]}
OUT.u8:    one uint8 mask per ROI, in Structure Set ROI order, each nz x ny x nx (i fastest).
Prints one line per ROI: its number, name, contour count and voxel count.
"""
import json
import sys

import numpy as np
import pydicom


def main():
    ds = pydicom.dcmread(sys.argv[1])
    grid = json.load(open(sys.argv[2]))
    origin = np.array(grid["origin"], float)
    spacing = np.array(grid["spacing"], float)
    direction = np.array(grid["direction"], float)
    nx, ny, nz = (int(n) for n in grid["dims"])
    assert ds.Modality == "RTSTRUCT", ds.Modality
    contours_of = {int(item.ReferencedROINumber): item for item in ds.ROIContourSequence}
    masks = []
    for roi in ds.StructureSetROISequence:
        number = int(roi.ROINumber)
        mask = np.zeros((nz, ny, nx), np.uint8)
        contours = getattr(contours_of[number], "ContourSequence", [])
        for c in contours:
            assert c.ContourGeometricType == "CLOSED_PLANAR", c.ContourGeometricType
            points = np.array([float(v) for v in c.ContourData], float).reshape(-1, 3)
            assert len(points) == int(c.NumberOfContourPoints)
            # LPS -> continuous index: D^T (p - origin) / spacing.
            ijk = ((points - origin) @ direction) / spacing
            k = int(round(ijk[0, 2]))
            assert np.all(np.abs(ijk[:, 2] - k) < 1e-3), f"contour off its plane: {ijk[:, 2]}"
            assert 0 <= k < nz, k
            fill_even_odd(mask[k], ijk[:, 0], ijk[:, 1])
        masks.append(mask)
        print(number, roi.ROIName, len(contours), int(mask.sum()))
    np.concatenate([m.ravel() for m in masks]).tofile(sys.argv[3])


def fill_even_odd(plane, xs, ys):
    """XORs into `plane` (ny x nx) the voxel centres inside the polygon (xs, ys)."""
    ny, nx = plane.shape
    i0, i1 = max(0, int(np.ceil(xs.min()))), min(nx - 1, int(np.floor(xs.max())))
    j0, j1 = max(0, int(np.ceil(ys.min()))), min(ny - 1, int(np.floor(ys.max())))
    if i0 > i1 or j0 > j1:
        return
    ii, jj = np.meshgrid(np.arange(i0, i1 + 1, dtype=float), np.arange(j0, j1 + 1, dtype=float))
    inside = np.zeros(ii.shape, bool)
    n = len(xs)
    for a in range(n):
        b = (a + 1) % n
        if ys[a] == ys[b]:
            continue  # parallel to the rows: both ends on one side of every row
        crosses_row = (ys[a] > jj) != (ys[b] > jj)
        x_cross = xs[a] + (jj - ys[a]) * (xs[b] - xs[a]) / (ys[b] - ys[a])
        inside ^= crosses_row & (ii < x_cross)
    plane[j0:j1 + 1, i0:i1 + 1] ^= inside.astype(np.uint8)


if __name__ == "__main__":
    main()
