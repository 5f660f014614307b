#pragma once
// An axis-aligned box [lo, hi] stored as a structure of patient P1 (an upload, no DICOM source):
// the app-layer tests' fixture whose volume and inside voxels are known without an oracle.

#include <gtest/gtest.h>

#include <string>

#include "core/geometry/primitives.h"
#include "db/store.h"
#include "db/surface_blob.h"

namespace soiq::server::testing {

// The new structure's id, or -1 (the test has failed) when the store refused it.
inline int64_t add_stored_box(db::Store& store, const Vec3& lo, const Vec3& hi, const std::string& name,
                              const std::string& study = "S1", const std::string& laterality = "") {
  db::NewStructure s;
  s.patient.patient_id = "P1";
  s.study.study_uid = study;
  s.name = name;
  s.laterality = laterality;
  Result<db::EncodedSurface> encoded = db::encode_surface(box(lo, hi));
  EXPECT_TRUE(encoded.ok());
  if (!encoded.ok()) return -1;
  s.surface = encoded->info;
  s.surface_blob = encoded->blob;
  Result<db::AddedStructure> added = store.add_structure(std::move(s));
  EXPECT_TRUE(added.ok()) << added.status().to_string();
  return added.ok() ? added->structure.id : -1;
}

}  // namespace soiq::server::testing
