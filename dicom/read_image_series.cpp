#include "dicom/read_image_series.h"

#include <bit>
#include <cstring>

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

// Stored pixel values -> modality values of one frame.
Result<std::vector<float>> decode_pixels(DcmDataset& ds, const std::string& path, int64_t count) {
  const uint16_t allocated = get_us(ds, DCM_BitsAllocated, 16);
  const uint16_t stored = get_us(ds, DCM_BitsStored, allocated);
  const uint16_t high_bit = get_us(ds, DCM_HighBit, stored - 1);
  const bool is_signed = get_us(ds, DCM_PixelRepresentation, 0) == 1;
  if (allocated != 8 && allocated != 16 && allocated != 32)
    return invalid_argument("'" + path + "': Bits Allocated " + std::to_string(allocated) + " is not supported");
  if (stored == 0 || stored > allocated || high_bit >= allocated || high_bit + 1 < stored)
    return invalid_argument("'" + path + "': inconsistent Bits Stored / High Bit");
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
  if (static_cast<int64_t>(n_bytes) < count * bytes_per_value)
    return data_loss("'" + path + "': Pixel Data has " + std::to_string(n_bytes) + " bytes, Rows x Columns needs " +
                     std::to_string(count * bytes_per_value));

  const double slope = get_number(ds, DCM_RescaleSlope).value_or(1.0);
  const double intercept = get_number(ds, DCM_RescaleIntercept).value_or(0.0);
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

Result<Slice> read_slice(const DicomInstance& inst, DcmDataset& ds) {
  const std::string& path = inst.path;
  Slice s;
  s.path = path;
  s.sop_instance_uid = inst.sop_instance_uid;
  s.info.label = "'" + path + "' (instance " + std::to_string(inst.instance_number) + ")";
  SOIQ_RETURN_IF_ERROR(decompress_pixels(ds, path));
  if (get_number(ds, DCM_NumberOfFrames).value_or(1) > 1)
    return invalid_argument("'" + path + "': multi-frame images are not supported");
  if (get_us(ds, DCM_SamplesPerPixel, 1) != 1)
    return invalid_argument("'" + path + "': colour images (Samples per Pixel > 1) are not supported");
  const auto ipp = get_numbers(ds, DCM_ImagePositionPatient, 3);
  const auto iop = get_numbers(ds, DCM_ImageOrientationPatient, 6);
  const auto ps = get_numbers(ds, DCM_PixelSpacing, 2);
  if (!ipp || !iop || !ps)
    return invalid_argument("slice " + s.info.label +
                            " lacks Image Position (Patient), Image Orientation (Patient) or Pixel Spacing");
  s.info.position_mm = {(*ipp)[0], (*ipp)[1], (*ipp)[2]};
  for (int i = 0; i < 6; ++i) s.info.orientation[i] = (*iop)[i];
  s.info.pixel_spacing_mm = {(*ps)[0], (*ps)[1]};
  s.info.rows = get_us(ds, DCM_Rows, 0);
  s.info.columns = get_us(ds, DCM_Columns, 0);
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
      if (!single_spacing) single_spacing = get_number(ds, DCM_SliceThickness);
      if (series.modality == "PT") pet = pet_tags(ds);
    }
    SOIQ_ASSIGN_OR_RETURN(Slice s, read_slice(inst, ds));
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
