// Imported structures as one RT Structure Set, on a real store: STS_002's CT and RT Structure Set
// imported, the GTV exported and imported back (RTSTRUCT -> soiq -> RTSTRUCT -> soiq), a synthetic
// surface with a hole and two parts stored on the CT series and taken the same way, and the
// refusals.
#include "server/app/structure_rt_struct.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "core/geometry/primitives.h"
#include "db/surface_blob.h"
#include "server/app/dicom_import.h"
#include "tests/db/temp_store.h"
#include "tests/support/sts_files.h"

namespace soiq::server {
namespace structure_rt_struct_test {

namespace fs = std::filesystem;
using db::testing::TempDir;

class StructureRtStruct : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string dir = tmp_.file("received");
    fs::create_directories(dir);
    const std::vector<std::string> sent = soiq::testing::copy_sts_002_ct(SOIQ_TEST_DATA_DIR, dir);
    Result<DicomImportResult> r = import_dicom_folder(*store_, dir, sent, int64_t(1) << 26, budget_, {});
    ASSERT_TRUE(r.ok()) << r.status().to_string();
    ASSERT_FALSE(r->structures.empty());
    gtv_ = r->structures[0].structure;
  }

  // The structure's voxels on its series by the 1D method, as soiqd converts it.
  RunLengthVolume voxels(const db::StructureRecord& s) {
    Result<db::SeriesRecord> series = store_->get_series(s.source_series_uid);
    EXPECT_TRUE(series.ok()) << series.status().to_string();
    if (!series.ok()) return {};
    auto admitted = features_.admit(s, series->geometry, {});
    EXPECT_TRUE(admitted.ok()) << admitted.status().to_string();
    if (!admitted.ok()) return {};
    auto v = features_.convert(*admitted, s, series->geometry, FillRule::kNonZero);
    EXPECT_TRUE(v.ok()) << v.status().to_string();
    return v.ok() ? v->volume : RunLengthVolume{};
  }

  // Exports `ids`, imports the file back and returns the structures that import stored.
  std::vector<db::StructureRecord> round_trip(const std::vector<int64_t>& ids, const std::string& name) {
    Result<BudgetedRtStruct> written = structure_rt_struct(*store_, features_, budget_, ids, "");
    EXPECT_TRUE(written.ok()) << written.status().to_string();
    if (!written.ok()) return {};
    const std::string dir = tmp_.file(name);
    fs::create_directories(dir);
    const std::string file = dir + "/rtstruct.dcm";
    std::ofstream(file, std::ios::binary) << written->rt_struct.bytes;
    Result<DicomImportResult> r = import_dicom_folder(*store_, dir, {file}, int64_t(1) << 26, budget_, {});
    EXPECT_TRUE(r.ok()) << r.status().to_string();
    if (!r.ok()) return {};
    for (const ImportProblem& p : r->problems) ADD_FAILURE() << p.message;
    std::vector<db::StructureRecord> out;
    for (const ImportedStructure& s : r->structures) out.push_back(s.structure);
    return out;
  }

  // Differing voxels of a and b, printed for the record.
  int64_t differing(const RunLengthVolume& a, const RunLengthVolume& b, const std::string& what) {
    auto cmp = compare(a, b);
    EXPECT_TRUE(cmp.ok()) << cmp.status().to_string();
    if (!cmp.ok()) return -1;
    EXPECT_GT(cmp->count_a, 0) << what;
    std::cout << what << ": " << cmp->count_a << " voxels before, " << cmp->only_a << " lost, " << cmp->only_b
              << " gained\n";
    return cmp->only_a + cmp->only_b;
  }

  TempDir tmp_;
  std::unique_ptr<db::SqliteStore> store_ = db::testing::open_store(tmp_.file("soiq.db"));
  MemoryBudget budget_{int64_t(1) << 30};
  FeatureEngine features_{*store_, int64_t(1) << 26, budget_};
  db::StructureRecord gtv_;
};

TEST_F(StructureRtStruct, ImportedStructureComesBackWithTheSameVoxels) {
  const std::vector<db::StructureRecord> back = round_trip({gtv_.id}, "gtv");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].name, gtv_.name);
  EXPECT_EQ(back[0].source_series_uid, gtv_.source_series_uid);
  EXPECT_EQ(differing(voxels(gtv_), voxels(back[0]), "STS_002 CT GTV round trip"), 0);
}

TEST_F(StructureRtStruct, SurfaceWithAHoleAndTwoPartsComesBackWithItsVoxels) {
  Result<db::SeriesRecord> ct = store_->get_series(gtv_.source_series_uid);
  ASSERT_TRUE(ct.ok());
  // A ring (a hole in its axial sections) and a ball beside it, around the middle of the CT.
  const ImageGeometry& g = ct->geometry;
  const Vec3 centre = g.index_to_physical({g.dims[0] / 2.0 + 0.3, g.dims[1] / 2.0 - 0.2, g.dims[2] / 2.0 + 0.1});
  const TriangleMesh mesh = merge(torus(centre, 30, 9, 48, 18), uv_sphere(centre + Vec3{52, 8, 3}, 10, 16, 24));
  db::NewStructure s;
  s.patient.patient_id = gtv_.patient_id;
  s.study.study_uid = gtv_.study_uid;
  s.name = "ring and ball";
  s.source_series_uid = gtv_.source_series_uid;
  s.source_uid = "synthetic/1";
  auto encoded = db::encode_surface(mesh);
  ASSERT_TRUE(encoded.ok());
  s.surface = encoded->info;
  s.surface_blob = encoded->blob;
  Result<db::AddedStructure> added = store_->add_structure(s);
  ASSERT_TRUE(added.ok()) << added.status().to_string();
  const std::vector<db::StructureRecord> back = round_trip({added->structure.id, gtv_.id}, "ring");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].name, "ring and ball");
  EXPECT_EQ(differing(voxels(added->structure), voxels(back[0]), "ring and ball round trip"), 0);
  EXPECT_EQ(differing(voxels(gtv_), voxels(back[1]), "GTV beside it"), 0);
}

TEST_F(StructureRtStruct, AnUnknownStructureIsNotFound) {
  EXPECT_EQ(structure_rt_struct(*store_, features_, budget_, {gtv_.id + 100}, "").status().code(),
            StatusCode::kNotFound);
}

TEST_F(StructureRtStruct, StructuresOfDifferentSeriesAreAnInvalidArgument) {
  db::NewStructure other = db::testing::new_structure(gtv_.patient_id, gtv_.study_uid, "elsewhere", 1);
  other.source_series_uid = "1.2.826.0.1.3680043.8.498.999";
  other.source_uid = "elsewhere/1";
  Result<db::AddedStructure> added = store_->add_structure(other);
  ASSERT_TRUE(added.ok()) << added.status().to_string();
  Result<BudgetedRtStruct> r = structure_rt_struct(*store_, features_, budget_, {gtv_.id, added->structure.id}, "");
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("export them separately"), std::string::npos) << r.status().message();
}

TEST_F(StructureRtStruct, AnUploadedStructureIsAFailedPreconditionThatSaysHowToImport) {
  Result<db::AddedStructure> uploaded = store_->add_structure(db::testing::new_structure("P", "S", "uploaded", 1));
  ASSERT_TRUE(uploaded.ok());
  Result<BudgetedRtStruct> r = structure_rt_struct(*store_, features_, budget_, {uploaded->structure.id}, "");
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(r.status().message().find("soiq import"), std::string::npos) << r.status().message();
}

TEST_F(StructureRtStruct, NoIdsOrARepeatedIdIsInvalidArgument) {
  EXPECT_EQ(structure_rt_struct(*store_, features_, budget_, {}, "").status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(structure_rt_struct(*store_, features_, budget_, {gtv_.id, gtv_.id}, "").status().code(),
            StatusCode::kInvalidArgument);
}

}  // namespace structure_rt_struct_test
}  // namespace soiq::server
