#pragma once
// The factor that turns PET voxel values (after rescale slope/intercept) into SUV body weight, or
// the reason there is none (SUV only where the files carry what it needs).
//
//   SUVbw = C(t) [Bq/ml] * W [g] / D(t)  with  D(t) = D0 * 2^(-(t - t0) / T_half)
//
// C: the voxel value in Bq/ml (Units (0054,1001) BQML); W: Patient's Weight (0010,1030) in kg x
// 1000; D0: Radionuclide Total Dose (0018,1074) in Bq; t0: Radiopharmaceutical Start (Date)Time
// (0018,1078 or 0018,1072); T_half: Radionuclide Half Life (0018,1075) in s; t: Series Date/Time
// (0008,0021/0031), else Acquisition Date/Time (0008,0022/0032) — the scan start to which the
// scanner decay-corrected, as Decay Correction (0054,1102) START says. Times without dates that
// give t < t0 are taken to cross midnight (t + 24 h). 1 ml of tissue is taken as 1 g.
//
// Output   factor with units "SUVbw" when every input is present and valid; factor 1 with units
//          "SUVbw" when Units is GML (the values already are SUV body weight); otherwise factor 1,
//          units as stored ("BQML", "CNTS", ... or "") and `note` saying what is missing.
// Cost     O(1); thread-safe.

#include <optional>
#include <string>

namespace soiq::dicom {

struct PetTags {
  std::string units;             // (0054,1001)
  std::string decay_correction;  // (0054,1102)
  std::optional<double> patient_weight_kg;
  std::optional<double> total_dose_bq;
  std::optional<double> half_life_s;
  std::string injection_datetime;        // DT YYYYMMDDHHMMSS(.f), "" when absent
  std::string injection_time;            // TM HHMMSS(.f)
  std::string series_date, series_time;  // DA, TM (Acquisition Date/Time when the series' are absent)
};

struct SuvScale {
  double factor = 1;
  std::string units;  // "SUVbw" when the values after scaling are SUV
  std::string note;   // why there is no SUV, "" when there is
};

SuvScale suv_body_weight(const PetTags& tags);

}  // namespace soiq::dicom
