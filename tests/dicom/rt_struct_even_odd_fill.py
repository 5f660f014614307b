#!/usr/bin/env python3
"""An independent reading of an RT Structure Set, for soiq's tests: pydicom parses the file and each
ROI's CLOSED_PLANAR contours are filled on a grid by the even-odd rule with the crossing-number
point-in-polygon test. A voxel centre is inside a contour iff a ray from it towards +i crosses an
odd number of the contour's edges, an edge end lying exactly on the ray's row counting as below
it ((y_a > y) != (y_b > y)), and a crossing exactly at the centre not being to its right; a voxel is inside the ROI iff it is inside an odd number of the ROI's contours on its
slice (PS3.3 C.8.8.6: holes and parts are separate contours). Shares no code with soiq.

usage: rt_struct_even_odd_fill.py RTSTRUCT GRID.json OUT.u8
       rt_struct_even_odd_fill.py RTSTRUCT --series DIR OUT.u8
GRID.json: {"origin": [x, y, z], "spacing": [si, sj, sk], "direction": [[...], [...], [...]]
            (rows; its columns are the unit directions of i, j, k in LPS), "dims": [nx, ny, nz]}
--series:  the image series' own files in DIR, read here: slices sorted along the normal of their
           planes, each contour on the slice whose plane it lies in (within 1e-3 mm), its points
           placed from that slice's own Image Position, so tilted and unevenly spaced stacks are
           taken as they are, with no grid between.
OUT.u8:    one uint8 mask per ROI, in Structure Set ROI order, each nz x ny x nx (i fastest).
Prints one line per ROI: its number, name, contour count and voxel count.
"""
import json
import sys

import numpy as np
import pydicom


def grid_mapping(path):
    """Contour points -> (k, i, j) through one affine grid (GRID.json)."""
    grid = json.load(open(path))
    origin = np.array(grid["origin"], float)
    spacing = np.array(grid["spacing"], float)
    direction = np.array(grid["direction"], float)
    nx, ny, nz = (int(n) for n in grid["dims"])
    assert np.allclose(direction.T @ direction, np.eye(3), atol=1e-4), "a sheared grid: read it with --series"

    def place(points):
        # LPS -> continuous index: D^T (p - origin) / spacing.
        ijk = ((points - origin) @ direction) / spacing
        k = int(round(ijk[0, 2]))
        assert np.all(np.abs(ijk[:, 2] - k) < 1e-3), f"contour off its plane: {ijk[:, 2]}"
        return k, ijk[:, 0], ijk[:, 1]

    return (nx, ny, nz), place


def series_mapping(directory):
    """Contour points -> (k, i, j) from the series' own slices, one by one."""
    import os
    slices = []
    for name in sorted(os.listdir(directory)):
        try:
            f = pydicom.dcmread(os.path.join(directory, name), stop_before_pixels=True)
        except Exception:
            continue
        if "ImagePositionPatient" not in f or f.get("Modality") == "RTSTRUCT":
            continue
        slices.append(f)
    o = np.array([float(v) for v in slices[0].ImageOrientationPatient])
    row, col = o[:3], o[3:]
    normal = np.cross(row, col)
    positions = sorted((np.array([float(v) for v in f.ImagePositionPatient]) for f in slices),
                       key=lambda p: float(p @ normal))
    sy, sx = (float(v) for v in slices[0].PixelSpacing)  # between rows, between columns
    heights = np.array([float(p @ normal) for p in positions])

    def place(points):
        h = float(np.median(points @ normal))
        k = int(np.argmin(np.abs(heights - h)))
        assert np.all(np.abs(points @ normal - heights[k]) < 1e-3), f"contour off slice {k}"
        d = points - positions[k]
        return k, (d @ row) / sx, (d @ col) / sy

    return (int(slices[0].Columns), int(slices[0].Rows), len(positions)), place


def main():
    ds = pydicom.dcmread(sys.argv[1])
    if sys.argv[2] == "--series":
        (nx, ny, nz), place = series_mapping(sys.argv[3])
        out_path = sys.argv[4]
    else:
        (nx, ny, nz), place = grid_mapping(sys.argv[2])
        out_path = sys.argv[3]
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
            k, xs, ys = place(points)
            assert 0 <= k < nz, k
            fill_even_odd(mask[k], xs, ys)
        masks.append(mask)
        print(number, roi.ROIName, len(contours), int(mask.sum()))
    np.concatenate([m.ravel() for m in masks]).tofile(out_path)


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
