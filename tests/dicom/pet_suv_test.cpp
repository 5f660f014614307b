// SUV body weight from the PET tags, against a hand computation of the formula in dicom/pet_suv.h.
#include "dicom/pet_suv.h"

#include <gtest/gtest.h>

#include <cmath>

namespace soiq::dicom {
namespace {

PetTags complete() {
  PetTags t;
  t.units = "BQML";
  t.decay_correction = "START";
  t.patient_weight_kg = 80;
  t.total_dose_bq = 400e6;
  t.half_life_s = 6586.2;  // 18F
  t.injection_time = "100000";
  t.series_date = "20200101";
  t.series_time = "110000.5";  // 3600.5 s later
  return t;
}

TEST(PetSuv, BodyWeightSuvFromDoseDecayedToTheScanStart) {
  const SuvScale s = suv_body_weight(complete());
  EXPECT_EQ(s.units, "SUVbw");
  EXPECT_EQ(s.note, "");
  const double dose_at_scan = 400e6 * std::exp2(-3600.5 / 6586.2);
  EXPECT_DOUBLE_EQ(s.factor, 80000.0 / dose_at_scan);
}

TEST(PetSuv, InjectionDateTimeIsUsedWhenBothDatesAreKnown) {
  PetTags t = complete();
  t.injection_datetime = "20191231230000";  // 12 h before the scan start, across midnight
  t.series_time = "110000";
  EXPECT_DOUBLE_EQ(suv_body_weight(t).factor, 80000.0 / (400e6 * std::exp2(-12 * 3600 / 6586.2)));
}

TEST(PetSuv, TimesAloneCrossMidnight) {
  PetTags t = complete();
  t.injection_time = "233000";
  t.series_time = "003000";
  EXPECT_DOUBLE_EQ(suv_body_weight(t).factor, 80000.0 / (400e6 * std::exp2(-3600 / 6586.2)));
}

TEST(PetSuv, GmlValuesAreAlreadySuv) {
  PetTags t;
  t.units = "GML";
  const SuvScale s = suv_body_weight(t);
  EXPECT_EQ(s.factor, 1);
  EXPECT_EQ(s.units, "SUVbw");
}

TEST(PetSuv, MissingWeightKeepsBqPerMlAndSaysWhy) {
  PetTags t = complete();
  t.patient_weight_kg.reset();
  const SuvScale s = suv_body_weight(t);
  EXPECT_EQ(s.factor, 1);
  EXPECT_EQ(s.units, "BQML");
  EXPECT_NE(s.note.find("Patient's Weight"), std::string::npos) << s.note;
}

TEST(PetSuv, DecayCorrectionOtherThanStartIsNotConverted) {
  PetTags t = complete();
  t.decay_correction = "ADMIN";
  const SuvScale s = suv_body_weight(t);
  EXPECT_EQ(s.units, "BQML");
  EXPECT_NE(s.note.find("Decay Correction START"), std::string::npos) << s.note;
}

}  // namespace
}  // namespace soiq::dicom
