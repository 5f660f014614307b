#include "dicom/seg_export.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dcostrmb.h>
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgfracon.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmiod/cielabutil.h>
#include <dcmtk/dcmiod/iodreferences.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>

#include "dicom/seg_bit_packing.h"

namespace soiq::dicom {
namespace {

// Pixel Data has a 32-bit length (even, so 0xFFFFFFFE at most).
constexpr int64_t kMaxPixelDataBytes = 0xFFFFFFFELL;

Status dcmtk_error(const std::string& what, const OFCondition& cond) {
  return internal_error("DICOM SEG: " + what + " (" + cond.text() + ")");
}

// A DS value (at most 16 characters, Part 5 6.2) with as many significant digits as fit: 16
// characters keep about 1e-11 mm of a position and 1e-13 of a direction cosine.
std::string format_ds(double v) {
  if (v == 0) return "0";  // also turns -0 into 0
  char buf[64];
  for (int precision = 16; precision > 0; --precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strlen(buf) <= 16) return buf;
  }
  return "0";
}

// The slices k that hold at least one voxel of v, ascending.
std::vector<int64_t> occupied_slices(const RunLengthVolume& v) {
  std::vector<int64_t> out;
  const int64_t ny = v.geometry.dims[1];
  for (int64_t k = 0; k < v.geometry.dims[2]; ++k)
    if (v.line_start[static_cast<size_t>(ny * (k + 1))] > v.line_start[static_cast<size_t>(ny * k)]) out.push_back(k);
  return out;
}

// Unpacked frame of slice k (one byte per pixel, row-major: rows = j, columns = i), as
// DcmSegmentation::addFrame takes it.
void fill_slice(const RunLengthVolume& v, int64_t k, std::vector<Uint8>& frame) {
  const int64_t nx = v.geometry.dims[0], ny = v.geometry.dims[1];
  std::fill(frame.begin(), frame.end(), Uint8{0});
  for (int64_t j = 0; j < ny; ++j) {
    const int64_t line = j + ny * k;
    for (int64_t r = v.line_start[static_cast<size_t>(line)]; r < v.line_start[static_cast<size_t>(line + 1)]; ++r) {
      const Run& run = v.runs[static_cast<size_t>(r)];
      std::fill(frame.begin() + j * nx + run.begin, frame.begin() + j * nx + run.end, Uint8{1});
    }
  }
}

Status validate(const SegSource& source, const std::vector<SegSegment>& segments, const SegWriteOptions& options,
                std::vector<std::vector<int64_t>>& slices_of_segment) {
  const ImageGeometry& g = source.geometry;
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  if (g.dims[0] < 1 || g.dims[1] < 1 || g.dims[0] > 65535 || g.dims[1] > 65535)
    return invalid_argument("source series grid is " + describe(g) + "; a SEG frame needs 1 to 65535 rows and columns");
  if (static_cast<int64_t>(source.slice_sop_instance_uids.size()) != g.dims[2])
    return invalid_argument("source series has " + std::to_string(source.slice_sop_instance_uids.size()) +
                            " slice SOP instance uids but its grid has " + std::to_string(g.dims[2]) + " slices");
  for (size_t k = 0; k < source.slice_sop_instance_uids.size(); ++k)
    if (source.slice_sop_instance_uids[k].empty())
      return invalid_argument("source series: slice " + std::to_string(k) + " has no SOP instance uid");
  const std::pair<const char*, const std::string*> required[] = {
      {"study uid", &source.study_uid},
      {"series uid", &source.series_uid},
      {"frame of reference uid", &source.frame_of_reference_uid},
      {"SOP class uid", &source.sop_class_uid}};
  for (const auto& [name, value] : required)
    if (value->empty()) return invalid_argument(std::string("source series has no ") + name);
  if (segments.empty()) return invalid_argument("no segments to write");
  if (segments.size() > 65535) return invalid_argument("a SEG holds at most 65535 segments");

  int64_t frames = 0;
  slices_of_segment.clear();
  for (size_t s = 0; s < segments.size(); ++s) {
    const SegSegment& seg = segments[s];
    const std::string name = "segment " + std::to_string(s + 1) + " ('" + seg.label + "')";
    if (seg.label.empty()) return invalid_argument("segment " + std::to_string(s + 1) + " has an empty label");
    if (seg.algorithm_type != SegAlgorithmType::kManual && seg.algorithm_name.empty())
      return invalid_argument(name + " needs an algorithm name unless its algorithm type is MANUAL");
    const Status same = check_same_grid(seg.volume.geometry, g);
    if (!same.ok())
      return invalid_argument(name + " is not on the source series grid (" + describe(g) + "): " + same.message());
    if (static_cast<int64_t>(seg.volume.line_start.size()) != seg.volume.line_count() + 1)
      return invalid_argument(name + ": malformed run-length volume (line_start has " +
                              std::to_string(seg.volume.line_start.size()) + " entries)");
    slices_of_segment.push_back(occupied_slices(seg.volume));
    if (slices_of_segment.back().empty()) return invalid_argument("structure '" + seg.label + "' has no voxels");
    frames += static_cast<int64_t>(slices_of_segment.back().size());
  }
  if (frames > options.max_frames)
    return resource_exhausted("the SEG would have " + std::to_string(frames) + " frames, over the limit of " +
                              std::to_string(options.max_frames) + "; write fewer segments per object");
  const int64_t bits = frames * g.dims[0] * g.dims[1];
  if ((bits + 7) / 8 > kMaxPixelDataBytes)
    return resource_exhausted("the SEG would have " + std::to_string((bits + 7) / 8) +
                              " bytes of pixel data, over DICOM's 32-bit limit; write fewer segments per object");
  return ok_status();
}

DcmSegTypes::E_SegmentAlgoType algo_type(SegAlgorithmType t) {
  switch (t) {
    case SegAlgorithmType::kManual:
      return DcmSegTypes::SAT_MANUAL;
    case SegAlgorithmType::kSemiautomatic:
      return DcmSegTypes::SAT_SEMIAUTOMATIC;
    case SegAlgorithmType::kAutomatic:
      return DcmSegTypes::SAT_AUTOMATIC;
  }
  return DcmSegTypes::SAT_UNKNOWN;
}

std::string new_uid(const char* root) {
  char buf[100];
  dcmGenerateUniqueIdentifier(buf, root);
  return buf;
}

// A Type 2 value copied from the source series, or "" when it does not fit its VR. The STS CTs'
// Study ID "IBSI_1_STS_002_CT" has 17 characters where SH allows 16: an empty Type 2 value says
// "unknown", a truncated one would name another study, and a copied one makes our object
// non-conformant (dciodvfy: "Length invalid for this VR").
std::string type2_value(const std::string& value, bool fits) { return fits ? value : ""; }

bool fits_date(const std::string& v) { return DcmDate::checkStringValue(v.c_str(), "1").good(); }
bool fits_time(const std::string& v) { return DcmTime::checkStringValue(v.c_str(), "1").good(); }
// SH: at most 16 characters (DCMTK 3.6.7 leaves the length unchecked); the SEG declares no
// Specific Character Set, so only the default repertoire (ASCII) fits and characters are bytes.
bool fits_short_string(const std::string& v) {
  return v.size() <= 16 && std::all_of(v.begin(), v.end(), [](unsigned char ch) { return ch >= 0x20 && ch < 0x7F; }) &&
         DcmShortString::checkStringValue(v.c_str(), "1").good();
}

// Patient, study, frame of reference and series of the new object.
Status set_identity(DcmSegmentation& seg, const SegSource& src, const SegWriteOptions& options,
                    const std::string& series_uid, const std::string& sop_uid) {
  const std::string sex =
      src.patient_sex == "M" || src.patient_sex == "F" || src.patient_sex == "O" ? src.patient_sex : "";
  const std::string birth_date = type2_value(src.patient_birth_date, fits_date(src.patient_birth_date));
  const std::string study_date = type2_value(src.study_date, fits_date(src.study_date));
  const std::string study_time = type2_value(src.study_time, fits_time(src.study_time));
  const std::string study_id = type2_value(src.study_id, fits_short_string(src.study_id));
  const std::string accession = type2_value(src.accession_number, fits_short_string(src.accession_number));
  // checkValue=OFFalse: the patient id is the key that links the SEG to its images, copied even
  // where DCMTK's VR checks would reject it (e.g. a trailing backslash that PACS happily store);
  // the other values were checked above.
  IODPatientModule& patient = seg.getPatient();
  OFCondition c = patient.setPatientID(src.patient_id.c_str(), OFFalse);
  if (c.good()) c = patient.setPatientName(src.patient_name.c_str(), OFFalse);
  if (c.good()) c = patient.setPatientSex(sex.c_str(), OFFalse);
  if (c.good()) c = patient.setPatientBirthDate(birth_date.c_str(), OFFalse);
  IODGeneralStudyModule& study = seg.getStudy();
  if (c.good()) c = study.setStudyInstanceUID(src.study_uid.c_str(), OFFalse);
  if (c.good()) c = study.setStudyDate(study_date.c_str(), OFFalse);
  if (c.good()) c = study.setStudyTime(study_time.c_str(), OFFalse);
  if (c.good()) c = study.setStudyID(study_id.c_str(), OFFalse);
  if (c.good()) c = study.setAccessionNumber(accession.c_str(), OFFalse);
  if (c.good()) c = seg.getFrameOfReference().setFrameOfReferenceUID(src.frame_of_reference_uid.c_str(), OFFalse);
  if (c.good()) c = seg.getSeries().setSeriesInstanceUID(series_uid.c_str());
  if (c.good()) c = seg.getSeries().setSeriesDescription(options.series_description.c_str(), OFFalse);
  if (c.good()) c = seg.getSegmentationSeriesModule().setSeriesNumber(std::to_string(options.series_number).c_str());
  if (c.good()) c = seg.getSOPCommon().setSOPInstanceUID(sop_uid.c_str());
  if (c.bad())
    return invalid_argument("DICOM SEG: a patient, study or series value was refused (" + std::string(c.text()) + ")");
  return ok_status();
}

Status add_segment(DcmSegmentation& seg, const SegSegment& s) {
  DcmSegment* raw = nullptr;
  OFCondition c = DcmSegment::create(
      raw, s.label.c_str(),
      CodeSequenceMacro(s.category.value.c_str(), s.category.scheme.c_str(), s.category.meaning.c_str()),
      CodeSequenceMacro(s.type.value.c_str(), s.type.scheme.c_str(), s.type.meaning.c_str()),
      algo_type(s.algorithm_type), s.algorithm_type == SegAlgorithmType::kManual ? "" : s.algorithm_name.c_str());
  std::unique_ptr<DcmSegment> segment(raw);
  if (c.bad() || !segment) return invalid_argument("segment '" + s.label + "' was refused (" + c.text() + ")");
  if (s.display_rgb) {
    double l = 0, a = 0, b = 0;
    const auto& rgb = *s.display_rgb;
    IODCIELabUtil::rgb2DicomLab(l, a, b, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
    c = segment->setRecommendedDisplayCIELabValue(
        static_cast<Uint16>(std::lround(l)), static_cast<Uint16>(std::lround(a)), static_cast<Uint16>(std::lround(b)));
    if (c.bad()) return dcmtk_error("colour of segment '" + s.label + "'", c);
  }
  Uint16 number = 0;
  c = seg.addSegment(segment.get(), number);
  if (c.bad()) return dcmtk_error("adding segment '" + s.label + "'", c);
  segment.release();  // owned by seg now
  return ok_status();
}

// Plane Orientation and Pixel Measures are the same for every frame. The Multi-frame Dimension
// module (Type 1) indexes frames by (segment number, plane position), the usual SEG organisation.
Status add_shared_groups(DcmSegmentation& seg, const ImageGeometry& g) {
  const Vec3 row{g.direction[0][0], g.direction[1][0], g.direction[2][0]};  // direction of increasing i
  const Vec3 col{g.direction[0][1], g.direction[1][1], g.direction[2][1]};  // direction of increasing j
  std::unique_ptr<FGPlaneOrientationPatient> orientation(FGPlaneOrientationPatient::createMinimal(
      format_ds(row[0]).c_str(), format_ds(row[1]).c_str(), format_ds(row[2]).c_str(), format_ds(col[0]).c_str(),
      format_ds(col[1]).c_str(), format_ds(col[2]).c_str()));
  if (!orientation) return internal_error("DICOM SEG: could not create the Plane Orientation group");
  OFCondition c = seg.addForAllFrames(*orientation);
  FGPixelMeasures measures;
  const std::string slice = format_ds(g.spacing_mm[2]);
  if (c.good()) c = measures.setPixelSpacing((format_ds(g.spacing_mm[1]) + "\\" + format_ds(g.spacing_mm[0])).c_str());
  if (c.good()) c = measures.setSliceThickness(slice.c_str());
  if (c.good()) c = measures.setSpacingBetweenSlices(slice.c_str());
  if (c.good()) c = seg.addForAllFrames(measures);
  if (c.bad()) return dcmtk_error("shared functional groups", c);
  const std::string organization = new_uid(SITE_INSTANCE_UID_ROOT);
  IODMultiframeDimensionModule& dims = seg.getDimensions();
  c = dims.addDimensionIndex(DCM_ReferencedSegmentNumber, organization.c_str(), DCM_SegmentIdentificationSequence,
                             "ReferencedSegmentNumber");
  if (c.good())
    c = dims.addDimensionIndex(DCM_ImagePositionPatient, organization.c_str(), DCM_PlanePositionSequence,
                               "ImagePositionPatient");
  if (c.bad()) return dcmtk_error("dimension index", c);
  return ok_status();
}

// Adds the frames of segment `s` to seg (for their functional groups) and their pixels to `pixels`, in
// the same order.
Status add_frames(DcmSegmentation& seg, const SegSource& src, const SegSegment& s, Uint16 segment_number,
                  const std::vector<int64_t>& slices, BinaryFramePacker& pixels) {
  const ImageGeometry& g = src.geometry;
  const CodeSequenceMacro derivation("113076", "DCM", "Segmentation");
  const CodeSequenceMacro purpose("121322", "DCM", "Source image for image processing operation");
  std::vector<Uint8> frame(static_cast<size_t>(g.dims[0] * g.dims[1]));
  for (int64_t k : slices) {
    const Vec3 p = g.index_to_physical({0, 0, static_cast<double>(k)});
    std::unique_ptr<FGPlanePosPatient> position(
        FGPlanePosPatient::createMinimal(format_ds(p[0]).c_str(), format_ds(p[1]).c_str(), format_ds(p[2]).c_str()));
    FGFrameContent content;
    OFCondition c = content.setDimensionIndexValues(segment_number, 0);
    if (c.good()) c = content.setDimensionIndexValues(static_cast<Uint32>(k + 1), 1);
    ImageSOPInstanceReferenceMacro ref;
    if (c.good()) c = ref.setReferencedSOPClassUID(src.sop_class_uid.c_str(), OFFalse);
    if (c.good())
      c = ref.setReferencedSOPInstanceUID(src.slice_sop_instance_uids[static_cast<size_t>(k)].c_str(), OFFalse);
    if (c.bad()) return dcmtk_error("frame of slice " + std::to_string(k) + " of '" + s.label + "'", c);
    OFVector<ImageSOPInstanceReferenceMacro> refs;
    refs.push_back(ref);
    std::unique_ptr<FGDerivationImage> derived(
        FGDerivationImage::createMinimal(refs, "voxels inside the structure", derivation, purpose));
    if (!position || !derived)
      return internal_error("DICOM SEG: could not create the groups of slice " + std::to_string(k) + " of '" + s.label +
                            "'");
    fill_slice(s.volume, k, frame);
    OFVector<FGBase*> groups;
    groups.push_back(position.get());
    groups.push_back(&content);
    groups.push_back(derived.get());
    pixels.add_frame(frame);                                 // first: addFrame may scribble on the buffer it packs
    c = seg.addFrame(frame.data(), segment_number, groups);  // copies the groups (its pixels are replaced)
    if (c.bad()) return dcmtk_error("frame of slice " + std::to_string(k) + " of '" + s.label + "'", c);
  }
  return ok_status();
}

// Referenced Series Sequence (Common Instance Reference module): the slices frames derive from.
Status add_references(DcmSegmentation& seg, const SegSource& src, const std::vector<std::vector<int64_t>>& slices) {
  std::vector<bool> used(src.slice_sop_instance_uids.size(), false);
  for (const auto& ks : slices)
    for (int64_t k : ks) used[static_cast<size_t>(k)] = true;
  IODReferences refs;
  size_t count = 0;
  for (size_t k = 0; k < used.size(); ++k) {
    if (!used[k]) continue;
    ++count;
    if (!refs.add(new IODImageReference(src.patient_id.c_str(), src.study_uid.c_str(), src.series_uid.c_str(),
                                        src.slice_sop_instance_uids[k].c_str(), src.sop_class_uid.c_str())))
      return internal_error("DICOM SEG: reference to slice " + std::to_string(k) + " was refused");
  }
  const size_t added = seg.getCommonInstanceReference().addReferences(refs, src.study_uid.c_str());
  if (added != count)
    return internal_error("DICOM SEG: " + std::to_string(added) + " of " + std::to_string(count) +
                          " slice references were written");
  return ok_status();
}

Result<std::string> to_part10(DcmFileFormat& file) {
  std::string out;
  std::vector<char> buffer(1 << 20);
  DcmOutputBufferStream stream(buffer.data(), static_cast<offile_off_t>(buffer.size()));
  file.transferInit();
  OFCondition c = EC_StreamNotifyClient;
  while (c == EC_StreamNotifyClient) {
    c = file.write(stream, EXS_LittleEndianExplicit, EET_ExplicitLength, nullptr);
    void* data = nullptr;
    offile_off_t length = 0;
    stream.flushBuffer(data, length);  // whatever the buffer holds, full or final
    out.append(static_cast<const char*>(data), static_cast<size_t>(length));
  }
  file.transferEnd();
  if (c.bad()) return dcmtk_error("encoding the file", c);
  return out;
}

}  // namespace

Result<WrittenSeg> write_seg(const SegSource& source, const std::vector<SegSegment>& segments,
                             const SegWriteOptions& options) {
  std::vector<std::vector<int64_t>> slices;
  SOIQ_RETURN_IF_ERROR(validate(source, segments, options, slices));
  // DCMTK's IOD checks log to stderr; what matters comes back as a Status.
  static std::once_flag quiet;
  std::call_once(quiet, [] {
    for (OFLogger* log : {&DCM_dcmsegLogger, &DCM_dcmfgLogger, &DCM_dcmiodLogger})
      log->setLogLevel(OFLogger::FATAL_LOG_LEVEL);
  });

  WrittenSeg out;
  out.series_uid = options.series_uid.empty() ? new_uid(SITE_SERIES_UID_ROOT) : options.series_uid;
  out.sop_instance_uid = options.sop_instance_uid.empty() ? new_uid(SITE_INSTANCE_UID_ROOT) : options.sop_instance_uid;

  DcmSegmentation* raw = nullptr;
  const IODGeneralEquipmentModule::EquipmentInfo equipment("soiq", "soiq", "1", "soiq");
  const ContentIdentificationMacro content("1", options.content_label.c_str(), options.content_description.c_str(), "");
  OFCondition c =
      DcmSegmentation::createBinarySegmentation(raw, static_cast<Uint16>(source.geometry.dims[1]),
                                                static_cast<Uint16>(source.geometry.dims[0]), equipment, content);
  std::unique_ptr<DcmSegmentation> seg(raw);
  if (c.bad() || !seg) return invalid_argument("DICOM SEG: cannot create it (" + std::string(c.text()) + ")");

  SOIQ_RETURN_IF_ERROR(set_identity(*seg, source, options, out.series_uid, out.sop_instance_uid));
  for (const SegSegment& s : segments) SOIQ_RETURN_IF_ERROR(add_segment(*seg, s));
  SOIQ_RETURN_IF_ERROR(add_shared_groups(*seg, source.geometry));
  BinaryFramePacker pixels;
  for (size_t s = 0; s < segments.size(); ++s)
    SOIQ_RETURN_IF_ERROR(add_frames(*seg, source, segments[s], static_cast<Uint16>(s + 1), slices[s], pixels));
  SOIQ_RETURN_IF_ERROR(add_references(*seg, source, slices));
  out.frame_count = static_cast<int64_t>(seg->getNumberOfFrames());

  DcmFileFormat file;
  c = seg->writeDataset(*file.getDataset());
  if (c.bad()) return dcmtk_error("DCMTK refused the object", c);
  // DCMTK 3.6.7 starts every frame on a byte boundary, which PS3.5 8.1.1 / 8.2 do not allow when
  // rows x columns is not a multiple of 8 (pydicom and other readers then shift every later frame):
  // its Pixel Data is replaced by ours, the frames' bits back to back.
  const std::vector<uint8_t> packed = pixels.bytes();
  c = file.getDataset()->putAndInsertUint8Array(DCM_PixelData, packed.data(),
                                                static_cast<unsigned long>(packed.size()));
  if (c.bad()) return dcmtk_error("setting the Pixel Data", c);
  SOIQ_ASSIGN_OR_RETURN(out.bytes, to_part10(file));
  return out;
}

}  // namespace soiq::dicom
