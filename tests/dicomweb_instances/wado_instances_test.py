"""WADO-RS of the instances soiqd kept, judged by pydicom (run by run_test.sh).

argv: BASE (soiqd keeping instances, with STS_002's CT and JPEG-LS MR imported), NONE (a soiqd with
--keep-instances off and the CT imported), ORIGIN (the CORS origin BASE allows), INFO (`soiq info`
of BASE), CT_DIR, MR_DIR (the original files).
"""
import email.parser
import glob
import json
import sys
import urllib.error
import urllib.request
from io import BytesIO

import numpy as np
import pydicom

base, none, origin, info_path, ct_dir, mr_dir = sys.argv[1:7]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what)


def get(url, headers=None, method="GET"):
    """(status, headers, body) of a request, errors included."""
    req = urllib.request.Request(url, headers=headers or {}, method=method)
    try:
        with urllib.request.urlopen(req) as r:
            return r.status, r.headers, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.headers, e.read()


def parts(headers, body):
    """The parts of a multipart/related body, by the standard library's MIME parser."""
    head = "Content-Type: " + headers["Content-Type"] + "\r\n\r\n"
    message = email.parser.BytesParser().parsebytes(head.encode() + body)
    return [(p.get_content_type(), p.get("Content-Type"), p.get_payload(decode=True)) for p in message.get_payload()]


def originals(folder):
    files = {}
    for path in sorted(glob.glob(folder + "/*.dcm")):
        raw = open(path, "rb").read()
        files[pydicom.dcmread(BytesIO(raw)).SOPInstanceUID] = raw
    return files


def json_get(url):
    status, _, body = get(url, {"Accept": "application/dicom+json"})
    check(status == 200, f"GET {url}: {status} {body[:200]}")
    return json.loads(body) if status == 200 else []


def value(item, tag):
    return item.get(tag, {}).get("Value", [None])[0]


for folder, modality in ((ct_dir, "CT"), (mr_dir, "MR")):
    files = originals(folder)
    first = pydicom.dcmread(BytesIO(next(iter(files.values()))))
    study, series = first.StudyInstanceUID, first.SeriesInstanceUID
    url = f"{base}/studies/{study}/series/{series}"

    # Metadata: every original SOP Instance UID once, with what a viewer lays the images out by.
    metadata = json_get(url + "/metadata")
    uids = [value(m, "00080018") for m in metadata]
    check(sorted(uids) == sorted(files), f"{modality} metadata lists {len(uids)} instances, not the {len(files)} originals")
    for m in metadata:
        ds = pydicom.dcmread(BytesIO(files[value(m, "00080018")]))
        check(value(m, "00280010") == ds.Rows and value(m, "00280011") == ds.Columns, f"{modality} Rows/Columns")
        check(m["00200032"]["Value"] == [float(x) for x in ds.ImagePositionPatient], f"{modality} ImagePositionPatient")
        check(m["00200037"]["Value"] == [float(x) for x in ds.ImageOrientationPatient], f"{modality} ImageOrientation")
        check(value(m, "00200052") == ds.FrameOfReferenceUID, f"{modality} FrameOfReferenceUID")
        check(m["7FE00010"]["BulkDataURI"].startswith(url + "/instances/"), f"{modality} BulkDataURI")

    # The series as stored: each part is one original file byte for byte.
    status, headers, body = get(url, {"Accept": 'multipart/related; type="application/dicom"; transfer-syntax=*'})
    check(status == 200, f"{modality} series retrieval: {status}")
    got = parts(headers, body)
    check(sorted(p[2] for p in got) == sorted(files.values()), f"{modality} series parts are not the original files")
    check(all("transfer-syntax=" in (p[1] or "") for p in got), f"{modality} parts name their transfer syntax")

    for uid, raw in list(files.items())[:6]:
        original = pydicom.dcmread(BytesIO(raw))
        expected = original.pixel_array  # pydicom's own decoding (GDCM for JPEG-LS)
        # Frames: native little endian, the values pydicom decodes from the original.
        status, headers, body = get(f"{url}/instances/{uid}/frames/1",
                                    {"Accept": 'multipart/related; type="application/octet-stream"; transfer-syntax=*'})
        check(status == 200, f"{modality} frame of {uid}: {status} {body[:200]}")
        if status == 200:
            (_, part_type, frame), = parts(headers, body)
            check("1.2.840.10008.1.2.1" in part_type, f"{modality} frame part type {part_type}")
            dtype = np.dtype(expected.dtype).newbyteorder("<")
            decoded = np.frombuffer(frame, dtype=dtype).reshape(expected.shape)
            check(np.array_equal(decoded, expected), f"{modality} frame of {uid} differs from pydicom's decoding")
        # The default syntax (Explicit VR Little Endian): decoded when the original was compressed,
        # the same pixels either way.
        status, headers, body = get(f"{url}/instances/{uid}", {"Accept": 'multipart/related; type="application/dicom"'})
        check(status == 200, f"{modality} instance {uid} in Explicit VR Little Endian: {status}")
        if status == 200:
            (_, _, part), = parts(headers, body)
            ds = pydicom.dcmread(BytesIO(part))
            check(ds.file_meta.TransferSyntaxUID == "1.2.840.10008.1.2.1", f"{modality} transcoded syntax")
            check(np.array_equal(ds.pixel_array, expected), f"{modality} transcoded pixels of {uid}")
            check(ds.SOPInstanceUID == uid, f"{modality} transcoded SOP Instance UID")

    status, _, body = get(f"{url}/instances/{uids[0]}/frames/2")
    check(status == 404 and b"has 1 frame" in body, f"{modality} frame 2 of a single-frame instance: {status} {body[:200]}")
    status, _, _ = get(f"{url}/instances/{uids[0]}/frames/1", {"Accept": 'multipart/related; type="image/jpeg"'})
    check(status == 406, f"{modality} frames as JPEG: {status}, not 406")
    status, _, _ = get(url, {"Accept": 'multipart/related; type="application/dicom"; transfer-syntax=1.2.840.10008.1.2.4.50'})
    check(status == 406, f"{modality} series as JPEG baseline: {status}, not 406")

# The study's metadata holds both series and the GTV SEGs and RT Structure Sets soiq writes; the
# SEG's frames reference the CT's own SOP Instance UIDs.
ct_files = originals(ct_dir)
study = pydicom.dcmread(BytesIO(next(iter(ct_files.values())))).StudyInstanceUID
everything = json_get(f"{base}/studies/{study}/metadata")
segs = [m for m in everything if value(m, "00080060") == "SEG"]
rt_structs = [m for m in everything if value(m, "00080060") == "RTSTRUCT"]
check(len(everything) == len(ct_files) + len(originals(mr_dir)) + len(segs) + len(rt_structs) and len(segs) >= 1
      and len(rt_structs) == len(segs), f"study metadata: {len(everything)} items")
seg_series = value(segs[0], "0020000E")
status, headers, body = get(f"{base}/studies/{study}/series/{seg_series}")
seg = pydicom.dcmread(BytesIO(parts(headers, body)[0][2]))
referenced = {f.DerivationImageSequence[0].SourceImageSequence[0].ReferencedSOPInstanceUID
              for f in seg.PerFrameFunctionalGroupsSequence}
check(referenced <= set(ct_files), "the SEG's frames reference instances soiqd does not serve")

# CORS: the allowed origin's preflight is answered without the token; answers carry its headers;
# another origin gets none.
status, headers, _ = get(f"{base}/studies", {"Origin": origin, "Access-Control-Request-Method": "GET",
                                             "Access-Control-Request-Headers": "authorization"}, method="OPTIONS")
# Once: Chromium refuses a preflight whose Access-Control-Allow-Origin holds two values.
check(status == 204 and headers.get_all("Access-Control-Allow-Origin") == [origin]
      and "Authorization" in headers.get("Access-Control-Allow-Headers", ""), f"preflight: {status} {headers.items()}")
status, headers, _ = get(f"{base}/studies", {"Origin": origin})
check(status == 200 and headers.get("Access-Control-Allow-Origin") == origin, "a GET from the allowed origin")
status, headers, _ = get(f"{base}/studies", {"Origin": "http://elsewhere.example"})
check(headers.get("Access-Control-Allow-Origin") is None, "a GET from another origin got CORS headers")
status, headers, _ = get(f"{base}/studies", {"Origin": "http://elsewhere.example", "Access-Control-Request-Method": "GET"},
                         method="OPTIONS")
check(status != 204 and headers.get("Access-Control-Allow-Origin") is None, f"another origin's preflight: {status}")

# Behind a token: the preflight is answered without it; a request without it is 401 that the viewer
# can read (CORS headers on errors too); with it, 200.
import os
tok, token = os.environ["SOIQ_TOKEN_BASE"], os.environ["SOIQ_TOKEN"]
status, headers, _ = get(f"{tok}/studies", {"Origin": origin, "Access-Control-Request-Method": "GET"}, method="OPTIONS")
check(status == 204 and headers.get("Access-Control-Allow-Origin") == origin, f"preflight with a token: {status}")
status, headers, body = get(f"{tok}/studies", {"Origin": origin})
check(status == 401 and headers.get("Access-Control-Allow-Origin") == origin, f"no token: {status} {dict(headers)}")
status, headers, _ = get(f"{tok}/studies", {"Origin": origin, "Authorization": "Bearer " + token})
check(status == 200 and headers.get("Access-Control-Allow-Origin") == origin, f"with the token: {status}")

# soiq info counts what is kept: the CT's and the MR's files, each once though the CT came twice.
info = open(info_path).read()
expected_files = len(ct_files) + len(originals(mr_dir))
expected_bytes = sum(len(b) for b in ct_files.values()) + sum(len(b) for b in originals(mr_dir).values())
line = f"{expected_files} in {expected_files} files, {expected_bytes} bytes"
check(line in info, f"soiq info does not say '{line}':\n{info}")

# Kept nowhere: the series is listed, and its instances are NOT_FOUND saying why.
series = pydicom.dcmread(BytesIO(next(iter(ct_files.values())))).SeriesInstanceUID
status, _, body = get(f"{none}/studies/{study}/series/{series}/metadata")
check(status == 404 and b"--keep-instances off" in body, f"--keep-instances off: {status} {body[:300]}")

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
