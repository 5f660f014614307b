#!/usr/bin/env python3
"""A real image series resampled onto a sheared stack, for soiq's tests: slice k keeps its plane and
orientation, but its first pixel moves in-plane by k x (DI, DJ) pixels (a gantry tilt of
atan(|shift| / spacing)) and its pixels are resampled there bilinearly from the original slice, so
the new stack is the same anatomy on other voxel centres: a new series, with new Series and SOP
Instance UIDs (derived from the old ones) in the same study. Other files (an RT Structure Set) are
copied with every reference to the old UIDs rewritten: its contours lie on the planes the slices
kept.

usage: shear_series.py IN_DIR OUT_DIR DI DJ [OTHER_DIR...]
OTHER_DIR: more files referring to the series (its RT Structure Set's directory), rewritten into OUT_DIR.
Prints the series' tilt in degrees.
"""
import math
import os
import sys
import warnings

import numpy as np
import pydicom
from pydicom.uid import ExplicitVRLittleEndian


def bilinear(pixels, di, dj):
    """pixels sampled at (column + di, row + dj); outside the slice: its nearest edge pixel."""
    rows, cols = pixels.shape
    x = np.clip(np.arange(cols, dtype=float) + di, 0, cols - 1)
    y = np.clip(np.arange(rows, dtype=float) + dj, 0, rows - 1)
    x0 = np.minimum(np.floor(x).astype(int), cols - 2)
    y0 = np.minimum(np.floor(y).astype(int), rows - 2)
    fx, fy = x - x0, y - y0
    p = pixels.astype(float)
    top = p[y0][:, x0] * (1 - fx) + p[y0][:, x0 + 1] * fx
    bottom = p[y0 + 1][:, x0] * (1 - fx) + p[y0 + 1][:, x0 + 1] * fx
    return top * (1 - fy)[:, None] + bottom * fy[:, None]


def renamed(uid):
    return pydicom.uid.generate_uid(entropy_srcs=["soiq shear_series.py", str(uid)])


def rewrite_references(ds, uids):
    """Every UI value of `ds`, nested sequences included, that names an old UID names its new one."""
    for element in ds.iterall():
        if element.VR == "UI" and not element.is_empty and str(element.value) in uids:
            element.value = uids[str(element.value)]


def main():
    warnings.simplefilter("ignore", UserWarning)  # the originals' over-long Study ID (SH), kept as it is
    src, dst, di, dj = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
    os.makedirs(dst, exist_ok=True)
    images, others = [], []
    for directory in [src] + sys.argv[5:]:
        for name in sorted(os.listdir(directory)):
            ds = pydicom.dcmread(os.path.join(directory, name))
            is_image = directory == src and "ImagePositionPatient" in ds and "PixelData" in ds
            (images if is_image else others).append((name, ds))
    uids = {}
    for _, ds in images + others:
        for old in (ds.SeriesInstanceUID, ds.SOPInstanceUID):
            uids[str(old)] = renamed(old)
    o = np.array([float(v) for v in images[0][1].ImageOrientationPatient])
    row, col = o[:3], o[3:]
    normal = np.cross(row, col)
    images.sort(key=lambda item: float(np.array([float(v) for v in item[1].ImagePositionPatient]) @ normal))
    sy, sx = (float(v) for v in images[0][1].PixelSpacing)
    for k, (name, ds) in enumerate(images):
        pixels = ds.pixel_array
        out = np.rint(bilinear(pixels, k * di, k * dj)).astype(pixels.dtype)
        position = np.array([float(v) for v in ds.ImagePositionPatient]) + k * di * sx * row + k * dj * sy * col
        ds.ImagePositionPatient = [f"{v:.6f}" for v in position]
        ds.PixelData = out.tobytes()
        rewrite_references(ds, uids)
        ds.file_meta.MediaStorageSOPInstanceUID = ds.SOPInstanceUID
        ds.file_meta.TransferSyntaxUID = ExplicitVRLittleEndian
        ds.is_little_endian, ds.is_implicit_VR = True, False
        ds.save_as(os.path.join(dst, name), write_like_original=False)
    for name, ds in others:
        rewrite_references(ds, uids)
        ds.file_meta.MediaStorageSOPInstanceUID = ds.SOPInstanceUID
        ds.save_as(os.path.join(dst, name), write_like_original=True)
    p0 = np.array([float(v) for v in images[0][1].ImagePositionPatient])
    p1 = np.array([float(v) for v in images[1][1].ImagePositionPatient])
    step = p1 - p0
    print(f"{math.degrees(math.acos(abs(step @ normal) / np.linalg.norm(step))):.3f}")


if __name__ == "__main__":
    main()
