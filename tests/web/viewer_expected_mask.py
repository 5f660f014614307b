"""The GTV SEG's voxels in patient space, computed without OHIF, for viewer_test.mjs to compare
OHIF's drawn overlay with (run by run_viewer_test.sh with Debian's pydicom and numpy).

argv: DICOMWEB_ROOT (soiqd's http://HOST:PORT/dicom-web, STS_002's CT imported) OUT_JSON.
The one SEG series soiqd lists (QIDO Modality=SEG) is retrieved by WADO-RS and decoded by pydicom;
each frame's CT image is the one it references (DerivationImageSequence), and that image's WADO-RS
metadata (ImagePositionPatient, ImageOrientationPatient, PixelSpacing) places every voxel centre in
LPS mm. Written per CT SOP Instance UID: the centres of the voxels inside, and of those outside
within 3 voxels (in the slice) of the inside: the ring, where a shifted or swollen overlay shows.
Each voxel is [x, y, z, flags]: INSIDE, RING, and DCMJS when the voxel is set in the frame as the
dcmjs bundled in OHIF 3.13.2 splits it (see dcmjs_frame): the test prints how well OHIF's drawing
agrees with that, so its known misdrawing is told from a new one.
"""
import email.parser
import json
import sys
import urllib.request
from io import BytesIO

import numpy as np
import pydicom

root, out = sys.argv[1:3]
RING = 3
INSIDE, IN_RING, DCMJS = 1, 2, 4


def get(url, accept):
    with urllib.request.urlopen(urllib.request.Request(url, headers={"Accept": accept})) as r:
        return r.headers, r.read()


def dicom_json(url):
    return json.loads(get(url, "application/dicom+json")[1])


def value(item, tag):
    return item.get(tag, {}).get("Value")


def parts(headers, body):
    """The bodies of a multipart/related answer, by the standard library's MIME parser."""
    head = "Content-Type: " + headers["Content-Type"] + "\r\n\r\n"
    message = email.parser.BytesParser().parsebytes(head.encode() + body)
    return [p.get_payload(decode=True) for p in message.get_payload()]


segs = dicom_json(f"{root}/series?Modality=SEG")
if len(segs) != 1:
    sys.exit(f"expected one SEG series in soiqd, QIDO lists {len(segs)}")
study = value(segs[0], "0020000D")[0]
seg_series = value(segs[0], "0020000E")[0]
bodies = parts(*get(f"{root}/studies/{study}/series/{seg_series}", 'multipart/related; type="application/dicom"'))
if len(bodies) != 1:
    sys.exit(f"the SEG series holds {len(bodies)} instances, not 1")
seg = pydicom.dcmread(BytesIO(bodies[0]))
frames = seg.pixel_array  # pydicom unpacks BINARY frames bit by bit, across byte boundaries
if frames.ndim == 2:
    frames = frames[np.newaxis]
ct_series = seg.ReferencedSeriesSequence[0].SeriesInstanceUID

# Every CT image's plane, by its SOP Instance UID.
planes = {}
for item in dicom_json(f"{root}/studies/{study}/series/{ct_series}/metadata"):
    planes[value(item, "00080018")[0]] = (
        np.array(value(item, "00200032"), float),
        np.array(value(item, "00200037"), float),
        np.array(value(item, "00280030"), float),
        int(value(item, "00200013")[0]),
    )


def dilate(mask, n):
    """mask grown by n voxels in the slice (a (2n+1) square)."""
    grown = mask.copy()
    rows, cols = mask.shape
    padded = np.pad(mask, n)
    for dr in range(-n, n + 1):
        for dc in range(-n, n + 1):
            grown |= padded[n + dr : n + dr + rows, n + dc : n + dc + cols]
    return grown


def centres(mask, plane):
    """The LPS mm centres of mask's voxels, in np.nonzero's order."""
    position, orientation, spacing, _ = plane
    r, c = np.nonzero(mask)
    # PS3.3 C.7.6.2.1.1: the first direction cosine goes along a row (column index), the second
    # down a column (row index); PixelSpacing is (between rows, between columns).
    points = position + np.outer(c * spacing[1], orientation[:3]) + np.outer(r * spacing[0], orientation[3:])
    return [[round(v, 3) for v in p] for p in points.tolist()]


def dcmjs_frame(packed, index, rows, columns):
    """Frame `index` as OHIF 3.13.2 decodes it. Its dcmjs (AsyncDicomReader.readUncompressedBitFrame,
    used when Rows x Columns is not a multiple of 8) copies each frame's bits out of the packed
    stream most significant bit first, while PS3.5 8.1.1 packs them least significant bit first, as
    the decoder after it reads them: a frame that starts on a byte boundary comes out right, the
    others have their bits moved within and across bytes."""
    n = rows * columns
    j = np.arange(n)
    b = 8 * (j // 8) + 7 - j % 8  # the frame's bit that dcmjs wrote where pixel j is read
    g = index * n + np.minimum(b, n - 1)
    bits = (packed[g // 8] >> (7 - g % 8)) & 1
    return np.where(b < n, bits, 0).astype(bool).reshape(rows, columns)


packed = np.frombuffer(seg.PixelData, np.uint8)
slices = {}
for i, frame in enumerate(frames):
    group = seg.PerFrameFunctionalGroupsSequence[i]
    sop = group.DerivationImageSequence[0].SourceImageSequence[0].ReferencedSOPInstanceUID
    if sop not in planes:
        sys.exit(f"SEG frame {i + 1} references {sop}, not an image of CT series {ct_series}")
    if sop in slices:  # one segment here: a second frame on the same image would be a bug
        sys.exit(f"SEG frames {slices[sop]['frame']} and {i + 1} reference the same image {sop}")
    inside = frame.astype(bool)
    ring = dilate(inside, RING) & ~inside
    dcmjs = dcmjs_frame(packed, i, seg.Rows, seg.Columns)
    flags = inside * INSIDE + ring * IN_RING + dcmjs * DCMJS
    slices[sop] = {
        "frame": i + 1,
        "instance_number": planes[sop][3],
        # Where the frame starts in its byte: 0 is where OHIF 3.13.2 draws it right.
        "bit_offset": (i * seg.Rows * seg.Columns) % 8,
        "inside": int(inside.sum()),
        "voxels": [p + [int(f)] for p, f in zip(centres(flags > 0, planes[sop]), flags[flags > 0])],
    }

with open(out, "w") as f:
    json.dump(
        {
            "study_uid": study,
            "seg_series_uid": seg_series,
            "ct_series_uid": ct_series,
            "rows": int(seg.Rows),
            "columns": int(seg.Columns),
            "frames": len(frames),
            "slices": slices,
        },
        f,
    )
total = sum(s["inside"] for s in slices.values())
print(f"expected mask: SEG {seg_series}, {len(frames)} frames of {seg.Rows}x{seg.Columns}, {total} voxels inside")
