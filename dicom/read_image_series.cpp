#include "dicom/read_image_series.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "dicom/dcmtk_file.h"
#include "dicom/decompress_pixels.h"
#include "dicom/pet_suv.h"
#include "dicom/slice_stack.h"

namespace soiq::dicom {
namespace {

static_assert(std::endian::native == std::endian::little, "pixel unpacking assumes a little-endian host");

struct Slice {
  SliceInfo info;
  std::vector<float> values;  // modality values (slope/intercept applied), rows x columns
  std::string sop_instance_uid;
  std::string path;
};

uint16_t get_us(DcmItem& item, const DcmTagKey& tag, uint16_t fallback) {
  Uint16 v = 0;
  return item.findAndGetUint16(tag, v).good() ? v : fallback;
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// A rescale value as the file gives it: nullopt when absent. A value that is present but no
// number is refused rather than read as the default: the file says something we cannot honour.
Result<std::optional<double>> rescale_value(DcmDataset& ds, const DcmTagKey& tag, const std::string& what,
                                            const std::string& path) {
  const std::string text = get_string(ds, tag);
  if (text.empty()) return std::optional<double>();
  const std::optional<double> v = get_number(ds, tag);
  if (!v) return invalid_argument("'" + path + "': " + what + " '" + text + "' is not a number; fix the tag");
  if (!std::isfinite(*v))
    return invalid_argument("'" + path + "': " + what + " '" + text + "' is not a finite number; fix the tag");
  return v;
}

// Stored pixel values -> modality values of one frame. The Pixel Data must be exactly what Rows,
// Columns, Number of Frames, Bits Allocated and Samples per Pixel describe (one byte of padding to
// an even length allowed): a header that disagrees with the data would have us read someone
// else's layout, or past the pixels, as an image.
Result<std::vector<float>> decode_pixels(DcmDataset& ds, const std::string& path, int64_t count) {
  const uint16_t allocated = get_us(ds, DCM_BitsAllocated, 16);
  const uint16_t stored = get_us(ds, DCM_BitsStored, allocated);
  const uint16_t high_bit = get_us(ds, DCM_HighBit, stored - 1);
  const bool is_signed = get_us(ds, DCM_PixelRepresentation, 0) == 1;
  if (allocated != 8 && allocated != 16 && allocated != 32)
    return invalid_argument("'" + path + "': Bits Allocated (0028,0100) " + std::to_string(allocated) +
                            " is not supported (8, 16 or 32)");
  if (stored == 0 || stored > allocated || high_bit >= allocated || high_bit + 1 < stored)
    return invalid_argument("'" + path + "': Bits Stored (0028,0101) " + std::to_string(stored) +
                            " and High Bit (0028,0102) " + std::to_string(high_bit) + " do not fit Bits Allocated " +
                            std::to_string(allocated));
  const Uint8* bytes = nullptr;
  unsigned long n_bytes = 0;
  if (allocated == 8) {
    if (ds.findAndGetUint8Array(DCM_PixelData, bytes, &n_bytes).bad() || bytes == nullptr)
      return data_loss("'" + path + "': no readable Pixel Data");
  } else {
    const Uint16* words = nullptr;
    unsigned long n_words = 0;
    if (ds.findAndGetUint16Array(DCM_PixelData, words, &n_words).bad() || words == nullptr)
      return data_loss("'" + path + "': no readable Pixel Data");
    bytes = reinterpret_cast<const Uint8*>(words);
    n_bytes = n_words * 2;
  }
  const int64_t bytes_per_value = allocated / 8;
  const int64_t needed = count * bytes_per_value;
  const int64_t have = static_cast<int64_t>(n_bytes);
  if (have != needed && !(needed % 2 == 1 && have == needed + 1))
    return invalid_argument("'" + path + "': Pixel Data (7FE0,0010) has " + std::to_string(have) +
                            " bytes but Rows (0028,0010) x Columns (0028,0011) x Bits Allocated (0028,0100) / 8 = " +
                            std::to_string(get_us(ds, DCM_Rows, 0)) + " x " +
                            std::to_string(get_us(ds, DCM_Columns, 0)) + " x " + std::to_string(bytes_per_value) +
                            " needs " + std::to_string(needed) + "; the header does not describe these pixels");

  SOIQ_ASSIGN_OR_RETURN(const std::optional<double> given_slope,
                        rescale_value(ds, DCM_RescaleSlope, "Rescale Slope (0028,1053)", path));
  SOIQ_ASSIGN_OR_RETURN(const std::optional<double> given_intercept,
                        rescale_value(ds, DCM_RescaleIntercept, "Rescale Intercept (0028,1052)", path));
  const double slope = given_slope.value_or(1.0);
  const double intercept = given_intercept.value_or(0.0);
  // Below float's smallest normal every stored value would become 0 (or a denormal): as useless
  // as a zero slope, and the sign of a subtle unit mistake.
  if (std::abs(slope) < std::numeric_limits<float>::min())
    return invalid_argument("'" + path + "': Rescale Slope (0028,1053) " + fmt(slope) +
                            " would make every voxel the same value; fix the tag");
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  if (std::abs(intercept) > kFloatMax)
    return invalid_argument("'" + path + "': Rescale Intercept (0028,1052) " + fmt(intercept) +
                            " is beyond float's range (" + fmt(kFloatMax) + "); fix the tag");
  // The extremes Bits Stored allows, not those this file happens to hold: a series is either
  // representable or not, whatever its content.
  const double lowest = is_signed ? -std::ldexp(1.0, stored - 1) : 0.0;
  const double highest = is_signed ? std::ldexp(1.0, stored - 1) - 1 : std::ldexp(1.0, stored) - 1;
  for (double v : {lowest, highest}) {
    const double modality = slope * v + intercept;
    if (std::abs(modality) > kFloatMax)
      return invalid_argument("'" + path + "': Rescale Slope (0028,1053) " + fmt(slope) + " takes stored value " +
                              fmt(v) + " to " + fmt(modality) + ", beyond float's range (" + fmt(kFloatMax) +
                              "); fix the tag");
  }

  const int shift = high_bit + 1 - stored;
  const uint64_t mask = stored == 64 ? ~uint64_t{0} : (uint64_t{1} << stored) - 1;
  std::vector<float> out(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i) {
    uint32_t raw = 0;
    std::memcpy(&raw, bytes + i * bytes_per_value, static_cast<size_t>(bytes_per_value));
    const uint64_t u = (static_cast<uint64_t>(raw) >> shift) & mask;
    const int64_t v = is_signed && (u >> (stored - 1)) & 1 ? static_cast<int64_t>(u) - (int64_t{1} << stored)
                                                           : static_cast<int64_t>(u);
    out[static_cast<size_t>(i)] = static_cast<float>(slope * static_cast<double>(v) + intercept);
  }
  return out;
}

PetTags pet_tags(DcmDataset& ds) {
  PetTags t;
  t.units = get_string(ds, DCM_Units);
  t.decay_correction = get_string(ds, DCM_DecayCorrection);
  t.patient_weight_kg = get_number(ds, DCM_PatientWeight);
  t.series_date = get_string(ds, DCM_SeriesDate);
  t.series_time = get_string(ds, DCM_SeriesTime);
  if (t.series_time.empty()) {
    t.series_date = get_string(ds, DCM_AcquisitionDate);
    t.series_time = get_string(ds, DCM_AcquisitionTime);
  }
  DcmItem* radio = nullptr;
  if (ds.findAndGetSequenceItem(DCM_RadiopharmaceuticalInformationSequence, radio, 0).good() && radio) {
    t.total_dose_bq = get_number(*radio, DCM_RadionuclideTotalDose);
    t.half_life_s = get_number(*radio, DCM_RadionuclideHalfLife);
    t.injection_datetime = get_string(*radio, DCM_RadiopharmaceuticalStartDateTime);
    t.injection_time = get_string(*radio, DCM_RadiopharmaceuticalStartTime);
  }
  return t;
}

// The size every slice of the series must have: the first slice's, checked before a slice's pixels
// are decoded so that a hostile Rows x Columns never sizes an allocation.
struct SliceSize {
  int64_t rows = 0, columns = 0;
};

Result<Slice> read_slice(const DicomInstance& inst, DcmDataset& ds, const std::optional<SliceSize>& expected) {
  const std::string& path = inst.path;
  Slice s;
  s.path = path;
  s.sop_instance_uid = inst.sop_instance_uid;
  s.info.label = "'" + path + "' (instance " + std::to_string(inst.instance_number) + ")";
  SOIQ_RETURN_IF_ERROR(decompress_pixels(ds, path));
  if (!get_string(ds, DCM_NumberOfFrames).empty()) {
    const std::optional<double> frames = get_number(ds, DCM_NumberOfFrames);
    if (frames && *frames > 1)
      return invalid_argument("'" + path + "': Number of Frames (0028,0008) is " + fmt(*frames) +
                              "; multi-frame images are not supported");
    if (!frames || *frames != 1)
      return invalid_argument("'" + path + "': Number of Frames (0028,0008) '" + get_string(ds, DCM_NumberOfFrames) +
                              "' is not a positive integer; fix the tag");
  }
  const uint16_t samples = get_us(ds, DCM_SamplesPerPixel, 1);
  if (samples != 1)
    return invalid_argument("'" + path + "': Samples per Pixel (0028,0002) is " + std::to_string(samples) +
                            "; colour images are not supported (1 is needed)");
  s.info.rows = get_us(ds, DCM_Rows, 0);
  s.info.columns = get_us(ds, DCM_Columns, 0);
  if (s.info.rows == 0) return invalid_argument("'" + path + "': Rows (0028,0010) is missing or 0");
  if (s.info.columns == 0) return invalid_argument("'" + path + "': Columns (0028,0011) is missing or 0");
  if (expected && (s.info.rows != expected->rows || s.info.columns != expected->columns))
    return invalid_argument("'" + path + "': Rows (0028,0010) x Columns (0028,0011) is " + std::to_string(s.info.rows) +
                            " x " + std::to_string(s.info.columns) + " but the series' first slice is " +
                            std::to_string(expected->rows) + " x " + std::to_string(expected->columns) +
                            "; a series must have one size");
  const auto ipp = get_numbers(ds, DCM_ImagePositionPatient, 3);
  const auto iop = get_numbers(ds, DCM_ImageOrientationPatient, 6);
  const auto ps = get_numbers(ds, DCM_PixelSpacing, 2);
  if (!ipp || !iop || !ps)
    return invalid_argument("slice " + s.info.label +
                            " lacks Image Position (Patient), Image Orientation (Patient) or Pixel Spacing");
  s.info.position_mm = {(*ipp)[0], (*ipp)[1], (*ipp)[2]};
  for (int i = 0; i < 6; ++i) s.info.orientation[i] = (*iop)[i];
  s.info.pixel_spacing_mm = {(*ps)[0], (*ps)[1]};
  SOIQ_ASSIGN_OR_RETURN(s.values, decode_pixels(ds, path, s.info.rows * s.info.columns));
  return s;
}

}  // namespace

Result<SeriesImage> read_image_series(const DicomSeries& series, int64_t max_voxels) {
  if (series.instances.empty()) return invalid_argument("series " + series.series_uid + " has no instances");
  SeriesImage out;
  out.series_uid = series.series_uid;
  out.modality = series.modality;
  std::vector<Slice> slices;
  std::optional<double> single_spacing;
  PetTags pet;
  for (const DicomInstance& inst : series.instances) {
    SOIQ_ASSIGN_OR_RETURN(auto file, load_dicom_file(inst.path, /*until_pixel_data=*/false));
    DcmDataset& ds = *file->getDataset();
    if (slices.empty()) {
      // Checked on the first slice, before the others' pixels are read.
      ImageGeometry g;
      g.dims = {get_us(ds, DCM_Columns, 0), get_us(ds, DCM_Rows, 0), static_cast<int64_t>(series.instances.size())};
      SOIQ_RETURN_IF_ERROR(check_grid_size(g, max_voxels));
      single_spacing = get_number(ds, DCM_SpacingBetweenSlices);
      const char* spacing_tag = "Spacing Between Slices (0018,0088)";
      if (!single_spacing) {
        single_spacing = get_number(ds, DCM_SliceThickness);
        spacing_tag = "Slice Thickness (0018,0050)";
      }
      // Only a single slice takes its spacing from these tags (slice_stack.h); there a value that
      // is no finite number would become the grid's spacing.
      if (series.instances.size() == 1 && single_spacing && !std::isfinite(*single_spacing))
        return invalid_argument("'" + inst.path + "': " + spacing_tag + " " + fmt(*single_spacing) +
                                " is not a finite number; fix the tag");
      if (series.modality == "PT") pet = pet_tags(ds);
    }
    std::optional<SliceSize> expected;
    if (!slices.empty()) expected = SliceSize{slices.front().info.rows, slices.front().info.columns};
    SOIQ_ASSIGN_OR_RETURN(Slice s, read_slice(inst, ds, expected));
    slices.push_back(std::move(s));
  }

  std::vector<SliceInfo> infos;
  for (const Slice& s : slices) infos.push_back(s.info);
  SOIQ_ASSIGN_OR_RETURN(StackGeometry stack, slice_stack(infos, single_spacing.value_or(1.0)));

  double factor = 1;
  if (series.modality == "CT") out.units = "HU";
  if (series.modality == "PT") {
    const SuvScale suv = suv_body_weight(pet);
    factor = suv.factor;
    out.units = suv.units;
    out.units_note = suv.note;
    // The SUV factor comes from dose, weight and times that a hostile or mistyped file can make
    // absurd; a factor that takes a voxel beyond float would store infinities.
    float largest = 0;
    for (const Slice& s : slices)
      for (float v : s.values) largest = std::max(largest, std::abs(v));
    if (!std::isfinite(factor) || std::abs(factor) * largest > std::numeric_limits<float>::max())
      return invalid_argument("series " + series.series_uid + ": the SUV factor " + fmt(factor) +
                              " from Patient's Weight (0010,1030), Radionuclide Total Dose (0018,1074) and Half "
                              "Life (0018,1075) takes voxel value " +
                              fmt(largest) + " beyond float's range; fix those tags");
  }
  out.image.geometry = stack.geometry;
  out.image.voxels.reserve(static_cast<size_t>(stack.geometry.voxel_count()));
  for (size_t k : stack.order) {
    Slice& s = slices[k];
    for (float v : s.values) out.image.voxels.push_back(static_cast<float>(factor * v));
    std::vector<float>().swap(s.values);
    out.slice_sop_instance_uids.push_back(s.sop_instance_uid);
    out.slice_paths.push_back(s.path);
  }
  return out;
}

}  // namespace soiq::dicom
