#!/usr/bin/env python3
"""Writes the seed corpora of fuzz/corpus/<harness>/: small valid inputs from which libFuzzer
mutates. Image and DICOM seeds are files of tests/data (the small ones, a few re-encoded by DCMTK's
dcmconv into other transfer syntaxes); meshes, which tests/data does not hold as files, and a few
image variants are written here, a unit cube or a 3 x 2 x 2 grid each, one per encoding the parser
knows. The corpora stay small (`du -sh fuzz/corpus`, < 2 MB) so libFuzzer's maximum input length
stays near the seeds'.

Run from the repository root: python3 fuzz/make_corpus.py   (pydicom 2.3, numpy; dcmtk's dcmconv)
"""
import base64
import gzip
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

OUT = "fuzz/corpus"
DATA = "tests/data"

CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_Q = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
CUBE_T = [t for q in CUBE_Q for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
SLICE_SEPARATOR = b"\nSOIQ-NEXT-SLICE\n"  # fuzz_dicom_series.cpp


def put(harness, name, data):
    os.makedirs(os.path.join(OUT, harness), exist_ok=True)
    with open(os.path.join(OUT, harness, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def copy(harness, name, path):
    with open(os.path.join(DATA, path), "rb") as f:
        put(harness, name, f.read())


def normal(t):
    a, b, c = (CUBE_V[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def meshes():
    s = "solid cube\n"
    for t in CUBE_T:
        s += " facet normal %g %g %g\n  outer loop\n" % normal(t)
        s += "".join("   vertex %g %g %g\n" % CUBE_V[i] for i in t)
        s += "  endloop\n endfacet\n"
    put("fuzz_stl", "cube_ascii.stl", s + "endsolid cube\n")
    b = b"binary cube".ljust(80, b" ") + struct.pack("<I", len(CUBE_T))
    for t in CUBE_T:
        b += struct.pack("<3f", *normal(t)) + b"".join(struct.pack("<3f", *CUBE_V[i]) for i in t) + b"\0\0"
    put("fuzz_stl", "cube_binary.stl", b)

    vs = "".join("v %g %g %g\n" % v for v in CUBE_V)
    put("fuzz_obj", "cube_quads.obj", "# cube\no cube\n" + vs + "".join("f %d %d %d %d\n" % tuple(i + 1 for i in q) for q in CUBE_Q))
    put("fuzz_obj", "cube_slashes.obj", vs + "vt 0 0\nvn 0 0 1\ng sides\ns off\n" +
        "".join("f %d/1/1 %d/1/1 %d/1/1\n" % tuple(i + 1 for i in t) for t in CUBE_T))
    put("fuzz_obj", "cube_negative.obj", vs + "vn 0 0 1\n" + "".join("f %d//1 %d//1 %d//1\n" % tuple(i - 8 for i in t) for t in CUBE_T))

    put("fuzz_off", "cube.off", "OFF\n# a unit cube\n8 6 12\n" + "".join("%g %g %g\n" % v for v in CUBE_V) +
        "".join("4 %d %d %d %d\n" % q for q in CUBE_Q))
    put("fuzz_off", "cube_triangles.off", "OFF 8 12 0\n" + "".join("%g %g %g\n" % v for v in CUBE_V) +
        "".join("3 %d %d %d 255 0 0\n" % t for t in CUBE_T))

    head = "ply\nformat %s 1.0\ncomment cube\nelement vertex 8\nproperty %s x\nproperty %s y\nproperty %s z\n" \
           "element face 6\nproperty list uchar int vertex_indices\nend_header\n"
    put("fuzz_ply", "cube_ascii.ply", head % ("ascii", "float", "float", "float") +
        "".join("%g %g %g\n" % v for v in CUBE_V) + "".join("4 %d %d %d %d\n" % q for q in CUBE_Q))
    for fmt, e in (("binary_little_endian", "<"), ("binary_big_endian", ">")):
        body = b"".join(struct.pack(e + "3d", *v) for v in CUBE_V) + b"".join(struct.pack(e + "B4i", 4, *q) for q in CUBE_Q)
        put("fuzz_ply", "cube_%s.ply" % fmt, (head % (fmt, "double", "double", "double")).encode() + body)

    legacy = "# vtk DataFile Version 3.0\ncube\n%s\nDATASET POLYDATA\nPOINTS 8 float\n"
    put("fuzz_vtk_polydata", "cube_ascii.vtk", legacy % "ASCII" + "".join("%g %g %g\n" % v for v in CUBE_V) +
        "POLYGONS 6 30\n" + "".join("4 %d %d %d %d\n" % q for q in CUBE_Q))
    put("fuzz_vtk_polydata", "cube_binary.vtk", (legacy % "BINARY").encode() +
        b"".join(struct.pack(">3f", *v) for v in CUBE_V) + b"\nTRIANGLE_STRIPS 6 30\n" +
        b"".join(struct.pack(">5i", 4, q[0], q[1], q[3], q[2]) for q in CUBE_Q) + b"\n")
    put("fuzz_vtk_polydata", "cube_v5.vtk", "# vtk DataFile Version 5.1\ncube\nASCII\nDATASET POLYDATA\n"
        "POINTS 8 float\n" + "".join("%g %g %g\n" % v for v in CUBE_V) + "POLYGONS 7 24\nOFFSETS vtktypeint64\n" +
        " ".join(str(4 * n) for n in range(7)) + "\nCONNECTIVITY vtktypeint64\n" +
        " ".join("%d %d %d %d" % q for q in CUBE_Q) + "\n")

    points = " ".join("%g %g %g" % v for v in CUBE_V)
    conn = " ".join("%d %d %d %d" % q for q in CUBE_Q)
    offs = " ".join(str(4 * (n + 1)) for n in range(6))
    xml = ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" '
           'header_type="UInt64">\n<PolyData>\n<Piece NumberOfPoints="8" NumberOfPolys="6">\n'
           '<Points><DataArray type="Float32" NumberOfComponents="3" format="%s">%s</DataArray></Points>\n'
           '<Polys><DataArray type="Int64" Name="connectivity" format="%s">%s</DataArray>\n'
           '<DataArray type="Int64" Name="offsets" format="%s">%s</DataArray></Polys>\n'
           '</Piece>\n</PolyData>\n</VTKFile>\n')
    put("fuzz_vtk_polydata", "cube_ascii.vtp", xml % ("ascii", points, "ascii", conn, "ascii", offs))

    def b64(fmt, values):
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        return base64.b64encode(struct.pack("<Q", len(data)) + data).decode()
    flat = [c for v in CUBE_V for c in v]
    put("fuzz_vtk_polydata", "cube_binary.vtp", xml % (
        "binary", b64("f", flat), "binary", b64("q", [i for q in CUBE_Q for i in q]),
        "binary", b64("q", [4 * (n + 1) for n in range(6)])))

    # zlib-compressed blocks (VTK's default writer output) and raw appended data, so mutations reach
    # the compression header and the appended offsets.
    def zlib_b64(fmt, values):
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        block = zlib.compress(data)
        header = struct.pack("<4I", 1, len(data), len(data), len(block))
        return base64.b64encode(header).decode() + base64.b64encode(block).decode()
    put("fuzz_vtk_polydata", "cube_zlib.vtp", xml.replace('header_type="UInt64"', 'compressor="vtkZLibDataCompressor"') % (
        "binary", zlib_b64("f", flat), "binary", zlib_b64("q", [i for q in CUBE_Q for i in q]),
        "binary", zlib_b64("q", [4 * (n + 1) for n in range(6)])))
    arrays = [struct.pack("<%df" % len(flat), *flat), struct.pack("<24i", *[i for q in CUBE_Q for i in q]),
              struct.pack("<6i", *[4 * (n + 1) for n in range(6)])]
    appended, offsets = b"", []
    for a in arrays:
        offsets.append(len(appended))
        appended += struct.pack("<I", len(a)) + a
    appended_xml = (
        '<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian">\n<PolyData>\n'
        '<Piece NumberOfPoints="8" NumberOfPolys="6">\n<Points><DataArray type="Float32" NumberOfComponents="3" '
        'format="appended" offset="%d"/></Points>\n<Polys><DataArray type="Int32" Name="connectivity" '
        'format="appended" offset="%d"/>\n<DataArray type="Int32" Name="offsets" format="appended" offset="%d"/>'
        '</Polys>\n</Piece>\n</PolyData>\n<AppendedData encoding="raw">\n_' % tuple(offsets))
    put("fuzz_vtk_polydata", "cube_appended_raw.vtp",
        appended_xml.encode() + appended + b"\n</AppendedData>\n</VTKFile>\n")


def nifti2(dims, datatype, bitpix, values):
    """A single-file NIfTI-2 (n+2) with an sform, as nibabel writes one."""
    h = struct.pack("<i8s2h8q3d8dq4d2d2q80s24s2i3d3d12d3i16sc15s",
                    540, b"n+2\0\r\n\x1a\n", datatype, bitpix, 3, *dims,
                    0, 0, 0,                                  # intent_p1..3
                    1, 2.0, 2.0, 2.0, 0, 0, 0, 0, 544,       # pixdim (qfac 1), vox_offset
                    1.0, 0.0, 0, 0, 0, 0, 0, 0,               # scl_slope, scl_inter, cal, slice timing
                    b"fuzz seed", b"", 0, 1,                  # descrip, aux_file, qform_code, sform_code
                    0, 0, 0, 0, 0, 0,                         # quatern, qoffset
                    -2, 0, 0, 10, 0, -2, 0, 20, 0, 0, 2, 30,  # srow_x, srow_y, srow_z (RAS)
                    0, 2, 0, b"", b"\0", b"")                # slice_code, xyzt_units (mm), intent
    assert len(h) == 540
    return h + b"\0" * 4 + values


def images():
    copy("fuzz_nifti", "ibsi_mask.nii.gz", "ibsi_digital_phantom/mask.nii.gz")
    copy("fuzz_nifti", "ibsi_phantom.nii.gz", "ibsi_digital_phantom/phantom.nii.gz")
    copy("fuzz_nifti", "sts_pet_mask.nii.gz", "sts/STS_002/PET_mask.nii.gz")
    with gzip.open(os.path.join(DATA, "ibsi_digital_phantom/phantom.nii.gz")) as f:
        put("fuzz_nifti", "ibsi_phantom.nii", f.read())
    put("fuzz_nifti", "grid_3x2x2_int16.nii2", nifti2((3, 2, 2, 1, 1, 1, 1), 4, 16, struct.pack("<12h", *range(12))))

    copy("fuzz_nrrd", "brain1_label_gzip.nrrd", "pyradiomics/brain1_label.nrrd")
    head = ("NRRD0004\n# fuzz seed\ntype: %s\ndimension: 3\nspace: %s\nsizes: 3 2 2\n"
            "space directions: (0.5,0,0) (0,0.75,0) (0,0,2)\nspace origin: (10,-5,20)\n"
            "endian: %s\nencoding: %s\n\n")
    put("fuzz_nrrd", "grid_raw.nrrd", (head % ("short", "left-posterior-superior", "little", "raw")).encode() +
        struct.pack("<12h", *range(12)))
    put("fuzz_nrrd", "grid_big_endian.nrrd", (head % ("float", "right-anterior-superior", "big", "raw")).encode() +
        struct.pack(">12f", *range(12)))
    put("fuzz_nrrd", "grid_ascii.nrrd", head % ("uchar", "LPS", "little", "ascii") + " ".join(map(str, range(12))) + "\n")

    meta = ("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
            "CompressedData = %s\n%sTransformMatrix = 1 0 0 0 1 0 0 0 1\nOffset = 10 -5 20\n"
            "ElementSpacing = 0.5 0.75 2\nDimSize = 3 2 2\nElementType = %s\nElementDataFile = LOCAL\n")
    raw = struct.pack("<12h", *range(12))
    put("fuzz_metaimage", "grid_raw.mha", (meta % ("False", "", "MET_SHORT")).encode() + raw)
    packed = zlib.compress(raw)
    put("fuzz_metaimage", "grid_zlib.mha", (meta % ("True", "CompressedDataSize = %d\n" % len(packed), "MET_SHORT")).encode() + packed)
    put("fuzz_metaimage", "grid_float.mha", (meta % ("False", "AnatomicalOrientation = RAI\n", "MET_FLOAT")).encode() +
        struct.pack("<12f", *range(12)))


def dicom_file(path):
    with open(os.path.join(DATA, path), "rb") as f:
        return f.read()


def dcmconv(path, option):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.dcm")
        subprocess.run(["dcmconv", option, os.path.join(DATA, path), out], check=True)
        with open(out, "rb") as f:
            return f.read()


def dicom():
    mr = "dicom/dicomdirtests/98892003/MR700/"
    put("fuzz_dicom_series", "mr700_3_slices", SLICE_SEPARATOR.join(dicom_file(mr + n) for n in ("4467", "4528", "4558")))
    ct = "dicom/dicomdirtests/77654033/CT2/"
    put("fuzz_dicom_series", "ct2_2_slices", SLICE_SEPARATOR.join(dicom_file(ct + n) for n in ("17106", "17136")))
    copy("fuzz_dicom_series", "mr_small.dcm", "dicom/MR_small.dcm")
    copy("fuzz_dicom_series", "sts_pet_slice.dcm", "sts/STS_002/dicom/PET/image/000000.dcm")
    copy("fuzz_dicom_series", "sts_mr_jpegls_slice.dcm", "sts/STS_002/dicom_jpegls/MR_T1/image/000000.dcm")
    put("fuzz_dicom_series", "mr700_big_endian.dcm", dcmconv(mr + "4467", "+tb"))
    put("fuzz_dicom_series", "mr700_implicit.dcm", dcmconv(mr + "4467", "+ti"))

    copy("fuzz_rt_struct", "pydicom_rtstruct.dcm", "dicom/rtstruct.dcm")
    copy("fuzz_rt_struct", "rt_utils_rt.dcm", "dicom/rt-utils/rt.dcm")
    put("fuzz_rt_struct", "rt_utils_rt_implicit.dcm", dcmconv("dicom/rt-utils/rt.dcm", "+ti"))

    copy("fuzz_seg", "standard_seg.dcm", "dicom/standard_seg.dcm")
    put("fuzz_seg", "standard_seg_implicit.dcm", dcmconv("dicom/standard_seg.dcm", "+ti"))
    put("fuzz_seg", "standard_seg_big_endian.dcm", dcmconv("dicom/standard_seg.dcm", "+tb"))


def expressions():
    for n, text in enumerate(["voxel_volume_mm3 > 50000", "mean[shell:5,PT] >= 2.5", "asym(voxel_volume_mm3)",
                              " asym( mean[inside,MR] ) != 0", "mean[,1.2.840.113619.2] <= -1e-3",
                              "voxel_count[core:2.5] == 12", "sphericity < .5", "shell:0.25", "core:3", "inside"]):
        put("fuzz_feature_expression", "expression_%02d" % n, text)


def dicomweb_requests():
    put("fuzz_dicomweb_request", "stow_two_parts",
        b"b1\r\n--b1\r\nContent-Type: application/dicom\r\n\r\nDICM\r\n--b1\r\n\r\nxx\r\n--b1--")
    put("fuzz_dicomweb_request", "qido_studies",
        "PatientID=AB*&StudyDate=20200101-20201231&limit=10&offset=2&includefield=all&fuzzymatching=true"
        "&PatientName=doe^jo")
    put("fuzz_dicomweb_request", "qido_series",
        "SeriesInstanceUID=2.25.1827659644562251692072282&Modality=SEG&SOPInstanceUID=1.2")
    put("fuzz_dicomweb_request", "soiq_query",
        "name=GTV*&where=voxel_volume_mm3>1000&select=mean[shell:5,PT]&order-by=asym(sphericity)&desc=true"
        "&spacing=1,1,2&margin=3")


def main():
    if not os.path.isdir(DATA):
        sys.exit("make_corpus.py: run from the repository root (no %s here)" % DATA)
    shutil.rmtree(OUT, ignore_errors=True)
    meshes()
    images()
    dicom()
    expressions()
    dicomweb_requests()


if __name__ == "__main__":
    main()
