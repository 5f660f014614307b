#!/usr/bin/env python3
"""Writes standard_seg.dcm: a small binary DICOM SEG packed as PS3.5 8.1.1 / 8.2 say (all frames'
bits back to back, least significant bit first, no padding between frames), made with pydicom
alone, as a third-party tool would, to test that soiq's import reads such files exactly.

Frames of 7 rows x 11 columns (77 bits, so every frame after the first starts mid-byte), two
segments, frames in no particular order (segment 2 first, slices shuffled). The grid: 11 x 7 x 6
voxels, spacing 0.9 x 1.2 x 3.0 mm, first voxel centre (10, -5.5, 20) mm, axis-aligned (LPS).

Run: python3 make_standard_seg.py standard_seg.dcm   (pydicom 2.3, numpy)
"""
import sys

import numpy as np
import pydicom
from pydicom.dataset import Dataset, FileMetaDataset
from pydicom.sequence import Sequence
from pydicom.uid import ExplicitVRLittleEndian

ROWS, COLS, SLICES = 7, 11, 6
SPACING = (0.9, 1.2, 3.0)  # along columns (i), rows (j), slices (k)
ORIGIN = (10.0, -5.5, 20.0)
SEG_CLASS = "1.2.840.10008.5.1.4.1.1.66.4"
CT_CLASS = "1.2.840.10008.5.1.4.1.1.2"
ROOT = "1.2.826.0.1.3680043.8.498.9917"  # pydicom's UID root + a fixed suffix: stable file


def uid(n):
    return f"{ROOT}.{n}"


def frame(segment, k):
    """A disc (segment 1) or a ring (segment 2) that moves with k, plus one corner pixel."""
    j, i = np.mgrid[0:ROWS, 0:COLS]
    r2 = (i - 3 - k) ** 2 + (j - 3) ** 2
    f = (r2 <= 5) if segment == 1 else ((r2 >= 4) & (r2 <= 9))
    f = f.astype(np.uint8)
    f[ROWS - 1, COLS - 1] = (k + segment) % 2  # the last bit of a frame
    f[0, 0] = k % 2  # the first bit of a frame
    return f


FRAMES = [(2, 4), (1, 0), (1, 3), (2, 1), (1, 1), (2, 2), (1, 5), (2, 5)]


def code(value, scheme, meaning):
    c = Dataset()
    c.CodeValue, c.CodingSchemeDesignator, c.CodeMeaning = value, scheme, meaning
    return c


def main(path):
    ds = Dataset()
    ds.SOPClassUID, ds.SOPInstanceUID = SEG_CLASS, uid(1)
    ds.PatientName, ds.PatientID, ds.PatientBirthDate, ds.PatientSex = "", "SEG-FIXTURE", "", "O"
    ds.StudyInstanceUID, ds.StudyDate, ds.StudyTime = uid(2), "20240102", "101112"
    ds.StudyID, ds.AccessionNumber, ds.ReferringPhysicianName = "S1", "A1", ""
    ds.Modality, ds.SeriesInstanceUID, ds.SeriesNumber = "SEG", uid(3), 901
    ds.SeriesDescription = "standard packing fixture"
    ds.FrameOfReferenceUID, ds.PositionReferenceIndicator = uid(4), ""
    ds.Manufacturer, ds.ManufacturerModelName = "pydicom fixture", "make_standard_seg.py"
    ds.DeviceSerialNumber, ds.SoftwareVersions = "1", pydicom.__version__
    ds.InstanceNumber, ds.ContentDate, ds.ContentTime = 1, "20240102", "101112"
    ds.ImageType = ["DERIVED", "PRIMARY"]
    ds.ContentLabel, ds.ContentDescription, ds.ContentCreatorName = "FIXTURE", "", ""
    ds.SamplesPerPixel, ds.PhotometricInterpretation = 1, "MONOCHROME2"
    ds.Rows, ds.Columns, ds.NumberOfFrames = ROWS, COLS, len(FRAMES)
    ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 1, 1, 0, 0
    ds.LossyImageCompression = "00"
    ds.SegmentationType = "BINARY"

    segments = []
    for n, label in ((1, "disc"), (2, "ring")):
        s = Dataset()
        s.SegmentNumber, s.SegmentLabel, s.SegmentAlgorithmType = n, label, "MANUAL"
        s.SegmentedPropertyCategoryCodeSequence = Sequence([code("85756007", "SCT", "Tissue")])
        s.SegmentedPropertyTypeCodeSequence = Sequence([code("85756007", "SCT", "Tissue")])
        segments.append(s)
    ds.SegmentSequence = Sequence(segments)

    org = uid(5)
    ds.DimensionOrganizationSequence = Sequence([Dataset()])
    ds.DimensionOrganizationSequence[0].DimensionOrganizationUID = org
    dims = []
    for pointer, group in (("ReferencedSegmentNumber", "SegmentIdentificationSequence"),
                           ("ImagePositionPatient", "PlanePositionSequence")):
        d = Dataset()
        d.DimensionOrganizationUID = org
        d.DimensionIndexPointer = pydicom.datadict.tag_for_keyword(pointer)
        d.FunctionalGroupPointer = pydicom.datadict.tag_for_keyword(group)
        dims.append(d)
    ds.DimensionIndexSequence = Sequence(dims)

    shared = Dataset()
    orient = Dataset()
    orient.ImageOrientationPatient = [1, 0, 0, 0, 1, 0]
    shared.PlaneOrientationSequence = Sequence([orient])
    measures = Dataset()
    measures.PixelSpacing = [SPACING[1], SPACING[0]]  # between rows, between columns
    measures.SliceThickness = SPACING[2]
    measures.SpacingBetweenSlices = SPACING[2]
    shared.PixelMeasuresSequence = Sequence([measures])
    ds.SharedFunctionalGroupsSequence = Sequence([shared])

    per_frame, pixels, referenced = [], [], []
    for segment, k in FRAMES:
        item = Dataset()
        content = Dataset()
        content.DimensionIndexValues = [segment, k + 1]
        item.FrameContentSequence = Sequence([content])
        pos = Dataset()
        pos.ImagePositionPatient = [ORIGIN[0], ORIGIN[1], ORIGIN[2] + k * SPACING[2]]
        item.PlanePositionSequence = Sequence([pos])
        ident = Dataset()
        ident.ReferencedSegmentNumber = segment
        item.SegmentIdentificationSequence = Sequence([ident])
        source = Dataset()
        source.ReferencedSOPClassUID, source.ReferencedSOPInstanceUID = CT_CLASS, uid(100 + k)
        source.PurposeOfReferenceCodeSequence = Sequence(
            [code("121322", "DCM", "Source image for image processing operation")])
        derivation = Dataset()
        derivation.DerivationCodeSequence = Sequence([code("113076", "DCM", "Segmentation")])
        derivation.SourceImageSequence = Sequence([source])
        item.DerivationImageSequence = Sequence([derivation])
        per_frame.append(item)
        pixels.append(frame(segment, k))
        if uid(100 + k) not in referenced:
            referenced.append(uid(100 + k))
    ds.PerFrameFunctionalGroupsSequence = Sequence(per_frame)

    series = Dataset()
    series.SeriesInstanceUID = uid(6)
    instances = []
    for r in sorted(referenced):
        inst = Dataset()
        inst.ReferencedSOPClassUID, inst.ReferencedSOPInstanceUID = CT_CLASS, r
        instances.append(inst)
    series.ReferencedInstanceSequence = Sequence(instances)
    ds.ReferencedSeriesSequence = Sequence([series])

    # The standard layout: the frames' bits in one stream, LSB first, padded once at the end.
    bits = np.concatenate([p.ravel() for p in pixels])
    packed = np.packbits(bits, bitorder="little").tobytes()
    if len(packed) % 2:
        packed += b"\0"
    ds.PixelData = packed
    ds["PixelData"].VR = "OB"

    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID, meta.MediaStorageSOPInstanceUID = SEG_CLASS, ds.SOPInstanceUID
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds.file_meta = meta
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.preamble = b"\0" * 128
    ds.save_as(path, write_like_original=False)


if __name__ == "__main__":
    main(sys.argv[1])
