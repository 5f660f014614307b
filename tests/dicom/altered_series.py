#!/usr/bin/env python3
"""A real image series altered into the stacks soiq must keep as they are, for soiq's tests, as a new
series (new Series and SOP Instance UIDs derived from the old ones and the alteration) in the same
study:

--shear DI DJ     slice k keeps its plane and orientation, but its first pixel moves in-plane by
                  h x (DI, DJ) pixels, h its height above the first slice in original slice
                  spacings (k before any thinning; a gantry tilt of atan(|shift| / spacing)), and
                  its pixels are resampled there bilinearly from the original slice: the same
                  anatomy on other voxel centres.
--thin FIRST LAST of the slices FIRST..LAST (in order along the normal), every other one is left
                  out, FIRST + 1 first: an unevenly spaced stack, finer outside that range.

Other files (an RT Structure Set, from OTHER_DIR...) are written beside the images with every
reference to the old UIDs renamed; contours on a plane whose slice was left out are left out
with it (they would lie on no image plane), and the rest lie on the planes the slices kept.

usage: altered_series.py IN_DIR OUT_DIR [--shear DI DJ] [--thin FIRST LAST] [OTHER_DIR...]
Prints the tilt in degrees and the slices kept.
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


def renamed(uid, how):
    """A new UID for `uid` altered `how` (the options): each alteration is a series of its own."""
    return pydicom.uid.generate_uid(entropy_srcs=["soiq altered_series.py", how, str(uid)])


def rewrite_references(ds, uids):
    """Every UI value of `ds`, nested sequences included, that names an old UID names its new one."""
    for element in ds.iterall():
        if element.VR == "UI" and not element.is_empty and str(element.value) in uids:
            element.value = uids[str(element.value)]


def position(ds):
    return np.array([float(v) for v in ds.ImagePositionPatient])


def drop_contours_off(ds, heights, normal):
    """Leaves out the contours of an RT Structure Set that lie on none of `heights` (along normal)."""
    for roi in getattr(ds, "ROIContourSequence", []):
        kept = []
        for c in getattr(roi, "ContourSequence", []):
            h = float(np.median(np.array([float(v) for v in c.ContourData]).reshape(-1, 3) @ normal))
            if np.min(np.abs(heights - h)) < 1e-3:
                kept.append(c)
        if "ContourSequence" in roi:
            roi.ContourSequence = kept


def main():
    warnings.simplefilter("ignore", UserWarning)  # the originals' over-long Study ID (SH), kept as it is
    args = sys.argv[1:]
    src, dst = args[0], args[1]
    shear, thin, others_dirs = (0.0, 0.0), None, []
    i = 2
    while i < len(args):
        if args[i] == "--shear":
            shear, i = (float(args[i + 1]), float(args[i + 2])), i + 3
        elif args[i] == "--thin":
            thin, i = (int(args[i + 1]), int(args[i + 2])), i + 3
        else:
            others_dirs, i = others_dirs + [args[i]], i + 1
    how = " ".join(a for a in args[2:] if a not in others_dirs)
    os.makedirs(dst, exist_ok=True)
    images, others = [], []
    for directory in [src] + others_dirs:
        for name in sorted(os.listdir(directory)):
            ds = pydicom.dcmread(os.path.join(directory, name))
            is_image = directory == src and "ImagePositionPatient" in ds and "PixelData" in ds
            (images if is_image else others).append((name, ds))
    uids = {}
    for _, ds in images + others:
        for old in (ds.SeriesInstanceUID, ds.SOPInstanceUID):
            uids[str(old)] = renamed(old, how)
    o = np.array([float(v) for v in images[0][1].ImageOrientationPatient])
    row, col = o[:3], o[3:]
    normal = np.cross(row, col)
    images.sort(key=lambda item: float(position(item[1]) @ normal))
    base = float(position(images[0][1]) @ normal)
    spacing = float(position(images[1][1]) @ normal) - base
    if thin:
        images = [item for k, item in enumerate(images) if not (thin[0] < k <= thin[1] and (k - thin[0]) % 2 == 1)]
    sy, sx = (float(v) for v in images[0][1].PixelSpacing)
    di, dj = shear
    for name, ds in images:
        if di or dj:
            h = (float(position(ds) @ normal) - base) / spacing
            pixels = ds.pixel_array
            ds.PixelData = np.rint(bilinear(pixels, h * di, h * dj)).astype(pixels.dtype).tobytes()
            moved = position(ds) + h * di * sx * row + h * dj * sy * col
            ds.ImagePositionPatient = [f"{v:.6f}" for v in moved]
        else:
            ds.PixelData = ds.pixel_array.tobytes()
        rewrite_references(ds, uids)
        ds.file_meta.MediaStorageSOPInstanceUID = ds.SOPInstanceUID
        ds.file_meta.TransferSyntaxUID = ExplicitVRLittleEndian
        ds.is_little_endian, ds.is_implicit_VR = True, False
        ds.save_as(os.path.join(dst, name), write_like_original=False)
    heights = np.array([float(position(ds) @ normal) for _, ds in images])
    for name, ds in others:
        rewrite_references(ds, uids)
        drop_contours_off(ds, heights, normal)
        ds.file_meta.MediaStorageSOPInstanceUID = ds.SOPInstanceUID
        ds.save_as(os.path.join(dst, name), write_like_original=True)
    step = position(images[1][1]) - position(images[0][1])
    tilt = math.degrees(math.acos(abs(step @ normal) / np.linalg.norm(step)))
    print(f"{tilt:.3f} degrees, {len(images)} slices")


if __name__ == "__main__":
    main()
