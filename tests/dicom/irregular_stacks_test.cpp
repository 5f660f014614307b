// Gantry-tilted and unevenly spaced stacks imported, converted and exported on their own voxel
// centres (a sheared grid, slice positions: never resampled), judged by pydicom with an independent
// even-odd fill that places every contour from its own slice's Image Position
// (rt_struct_even_odd_fill.py --series): synthetic CTs with an ellipsoid's RT Structure Set written
// with DCMTK, and STS_002's CT altered (altered_series.py: resampled onto a sheared stack, thinned
// to uneven spacing, or both) with its real RT Structure Set.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "core/features/structure_features.h"
#include "core/geometry/slice_sections.h"
#include "core/voxelize/voxelize_1d.h"
#include "ct_slice_writer.h"
#include "dicom/import_dicom.h"
#include "dicom/read_image_series.h"
#include "dicom/read_rt_struct.h"
#include "dicom/read_seg.h"
#include "dicom/rt_struct_export.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"
#include "rt_struct_writer.h"
#include "seg_source_of.h"
#include "seg_test_support.h"

namespace soiq::dicom {
namespace irregular_stacks_test {

using testing::data_dir;
using testing::TempDir;

constexpr double kPixel = 0.661468;  // CT_small's pixel spacing
constexpr double kDegree = std::numbers::pi / 180;

// A synthetic stack: CT_small's 128 x 128 pixels on planes of the given row and column directions,
// slice k's first pixel at firsts[k].
struct Stack {
  std::string name;
  Vec3 row, col;
  std::vector<Vec3> firsts;
  bool tilted = false, uneven = false;
};

void PrintTo(const Stack& s, std::ostream* os) { *os << s.name; }

// The classic gantry tilt (planes tilted 15 degrees about the rows, the table moving 3 mm along z
// per slice); a CT finer through the middle (1.5 mm) than at its ends (5 and 4 mm); and both.
std::vector<Stack> stacks() {
  const Vec3 first{-158.135803, -179.035797, -75.7};
  const double t = 15 * kDegree;
  const Vec3 tilted_col{0, std::cos(t), -std::sin(t)};
  const std::vector<double> even = {0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 33, 36, 39, 42, 45};
  const std::vector<double> uneven = {0, 5, 10, 14, 16, 17.5, 19, 20.5, 22, 23.5, 25, 26.5, 28, 30, 34, 38, 42, 46};
  auto along_z = [&](const std::vector<double>& z) {
    std::vector<Vec3> out;
    for (const double h : z) out.push_back(first + Vec3{0, 0, h});
    return out;
  };
  return {{"tilted 15 degrees", {1, 0, 0}, tilted_col, along_z(even), true, false},
          {"unevenly spaced", {1, 0, 0}, {0, 1, 0}, along_z(uneven), false, true},
          {"tilted and unevenly spaced", {1, 0, 0}, tilted_col, along_z(uneven), true, true}};
}

// An ellipsoid inside every stack: centre and semi-axes along L, P, S.
const Vec3 kCentre{-116, -140, -53};
const Vec3 kSemi{17, 13, 11};

double form(const Vec3& p) {
  const Vec3 d = p - kCentre;
  return std::pow(d[0] / kSemi[0], 2) + std::pow(d[1] / kSemi[1], 2) + std::pow(d[2] / kSemi[2], 2);
}

// The ellipsoid's section by the plane through `o` spanned by `row` and `col`, as 96 points: rays
// from the section's centre (the plane's point of least form, a 2x2 solve) out to where the form
// reaches 1. Empty when the plane misses or grazes it.
std::vector<Vec3> section(const Vec3& o, const Vec3& row, const Vec3& col) {
  // form(o + u row + v col) = |S (o - c) + u S row + v S col|^2 with S = diag(1 / semi).
  auto scaled = [](const Vec3& v) { return Vec3{v[0] / kSemi[0], v[1] / kSemi[1], v[2] / kSemi[2]}; };
  const Vec3 a = scaled(row), b = scaled(col), r0 = scaled(o - kCentre);
  const double aa = dot(a, a), ab = dot(a, b), bb = dot(b, b), ar = dot(a, r0), br = dot(b, r0);
  const double det = aa * bb - ab * ab;
  const double u0 = (-ar * bb + br * ab) / det, v0 = (-br * aa + ar * ab) / det;
  const Vec3 centre = o + u0 * row + v0 * col;
  if (form(centre) >= 0.97) return {};
  std::vector<Vec3> points;
  for (int n = 0; n < 96; ++n) {
    const double t = 2 * std::numbers::pi * n / 96;
    const Vec3 d = std::cos(t) * row + std::sin(t) * col;
    const Vec3 sd = scaled(d), sc = scaled(centre - kCentre);
    const double qa = dot(sd, sd), qb = 2 * dot(sd, sc), qc = dot(sc, sc) - 1;
    const double s = (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
    points.push_back(centre + s * d);
  }
  return points;
}

// The stack's CT (DCMTK, from CT_small) and the ellipsoid's RT Structure Set, in `dir`.
void write_study(const Stack& stack, const TempDir& dir) {
  char orientation[128];
  std::snprintf(orientation, sizeof orientation, "%.9f\\%.9f\\%.9f\\%.9f\\%.9f\\%.9f", stack.row[0], stack.row[1],
                stack.row[2], stack.col[0], stack.col[1], stack.col[2]);
  testing::write_ct_series(dir, int(stack.firsts.size()), [&](DcmDataset& ds, int k) {
    const Vec3& p = stack.firsts[size_t(k)];
    char position[96];
    std::snprintf(position, sizeof position, "%.6f\\%.6f\\%.6f", p[0], p[1], p[2]);
    ASSERT_TRUE(ds.putAndInsertString(DCM_ImagePositionPatient, position).good());
    ASSERT_TRUE(ds.putAndInsertString(DCM_ImageOrientationPatient, orientation).good());
  });
  std::vector<std::vector<Vec3>> contours;
  for (const Vec3& first : stack.firsts)
    if (auto s = section(first, stack.row, stack.col); !s.empty()) contours.push_back(std::move(s));
  ASSERT_GT(contours.size(), 5u);
  testing::write_rt_struct(dir.file("rtstruct.dcm"), "ELLIPSOID", contours, testing::kSyntheticCtSeriesUid);
}

// pydicom's reading of `rtstruct`'s first ROI on the series in `series_dir`, slice by slice.
RunLengthVolume pydicom_reading(const std::string& rtstruct, const std::string& series_dir, const ImageGeometry& g,
                                const TempDir& tmp) {
  Mask out{g, std::vector<uint8_t>(size_t(g.voxel_count()), 0)};
  const std::string python = testing::python_with_pydicom();
  EXPECT_FALSE(python.empty()) << "no python3 with pydicom and numpy (scripts/install-deps)";
  const std::string mask = tmp.file("pydicom_mask.u8");
  int status = 0;
  const std::string log = testing::run_command(python + " " + data_dir("../dicom/rt_struct_even_odd_fill.py") + " " +
                                                   rtstruct + " --series " + series_dir + " " + mask,
                                               status);
  EXPECT_EQ(status, 0) << log;
  std::ifstream in(mask, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_GE(bytes.size(), out.voxels.size());
  for (size_t n = 0; n < out.voxels.size() && n < bytes.size(); ++n) out.voxels[n] = uint8_t(bytes[n]);
  return from_mask(out);
}

int64_t differing(const RunLengthVolume& got, const RunLengthVolume& expected, const std::string& what) {
  auto cmp = compare(got, expected);
  EXPECT_TRUE(cmp.ok()) << cmp.status().to_string();
  if (!cmp.ok()) return -1;
  EXPECT_GT(cmp->count_b, 0) << what;
  std::cout << what << ": " << cmp->count_b << " voxels expected, " << cmp->only_a << " only in ours, " << cmp->only_b
            << " only expected\n";
  return cmp->only_a + cmp->only_b;
}

struct Imported {
  DicomImport import;
  SegSource source;
  const ImportedStructure* structure = nullptr;
};

Imported import_study(const std::vector<std::string>& paths) {
  Imported out;
  auto imported = import_dicom(paths);
  EXPECT_TRUE(imported.ok()) << imported.status().to_string();
  if (!imported.ok()) return out;
  out.import = std::move(*imported);
  EXPECT_EQ(out.import.structure_sets.size(), 1u);
  for (const FileProblem& p : out.import.problems) ADD_FAILURE() << p.path << ": " << p.status.to_string();
  if (out.import.structure_sets.size() != 1) return out;
  const ImportedStructureSet& set = out.import.structure_sets[0];
  auto source = testing::seg_source_of(out.import, set.referenced_series_uid);
  EXPECT_TRUE(source.ok()) << source.status().to_string();
  if (!source.ok() || set.converted.structures.empty()) return out;
  out.source = *source;
  out.structure = &set.converted.structures[0];
  return out;
}

class IrregularStack : public ::testing::TestWithParam<Stack> {};

TEST_P(IrregularStack, SeriesGridPassesThroughEverySlicesOwnPixels) {
  const Stack& stack = GetParam();
  TempDir tmp;
  write_study(stack, tmp);
  const Imported study = import_study({tmp.path()});
  ASSERT_NE(study.structure, nullptr);
  const ImageGeometry& g = study.source.geometry;
  EXPECT_EQ(g.sheared(), stack.tilted) << describe(g);
  EXPECT_EQ(g.uneven(), stack.uneven) << describe(g);
  if (stack.tilted) {
    EXPECT_NEAR(g.tilt_degrees(), 15, 1e-4);
  }
  for (size_t k = 0; k < stack.firsts.size(); ++k) {
    const Vec3 want = stack.firsts[k] + (5 * kPixel) * stack.row + (7 * kPixel) * stack.col;
    const Vec3 got = g.index_to_physical({5, 7, double(k)});
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[size_t(a)], want[size_t(a)], 1e-5) << "slice " << k;
  }
}

TEST_P(IrregularStack, ImportedContoursEqualPydicomsFillOnEachSlice) {
  const Stack& stack = GetParam();
  TempDir tmp;
  write_study(stack, tmp);
  const Imported study = import_study({tmp.path()});
  ASSERT_NE(study.structure, nullptr);
  EXPECT_EQ(study.structure->contours_outside_grid, 0);
  const RunLengthVolume oracle = pydicom_reading(tmp.file("rtstruct.dcm"), tmp.path(), study.source.geometry, tmp);
  EXPECT_EQ(differing(study.structure->volume, oracle, stack.name + " ellipsoid, import vs pydicom"), 0);
  // The voxels' volume (each slice's voxels times their own volume) is the ellipsoid's to within
  // the slices' sampling of its ends; the feature engine measures it so, and the surface (marching
  // cubes of the mask, in mm) agrees.
  auto report =
      structure_features({study.structure->volume, std::make_shared<const TriangleMesh>(study.structure->surface)}, {});
  ASSERT_TRUE(report.ok()) << report.status().to_string();
  std::map<std::string, double> f;
  for (const Feature& x : report->features)
    if (x.region.empty() && x.value.size() == 1) f[x.name] = x.value[0];
  const ImageGeometry& g = study.source.geometry;
  double volume = 0;
  for (int64_t k = 0; k < g.dims[2]; ++k) {
    int64_t count = 0;
    for (int64_t l = g.dims[1] * k; l < g.dims[1] * (k + 1); ++l)
      for (int64_t r = study.structure->volume.line_start[size_t(l)];
           r < study.structure->volume.line_start[size_t(l) + 1]; ++r)
        count += study.structure->volume.runs[size_t(r)].end - study.structure->volume.runs[size_t(r)].begin;
    volume += double(count) * g.voxel_volume_mm3(k);
  }
  const double analytic = 4.0 / 3.0 * std::numbers::pi * kSemi[0] * kSemi[1] * kSemi[2];
  std::cout << stack.name << " ellipsoid: " << volume << " mm3 from voxels, " << f["mesh_volume_mm3"]
            << " inside its surface, analytic " << analytic << "\n";
  EXPECT_NEAR(volume, analytic, 0.04 * analytic);
  EXPECT_NEAR(f["voxel_volume_mm3"], volume, 1e-9 * volume);
  EXPECT_NEAR(f["mesh_volume_mm3"], volume, 0.04 * volume);
}

TEST_P(IrregularStack, SegAndRtStructExportsReadBackOnTheSameSlices) {
  const Stack& stack = GetParam();
  TempDir tmp;
  write_study(stack, tmp);
  const Imported study = import_study({tmp.path()});
  ASSERT_NE(study.structure, nullptr);
  const ImageGeometry& g = study.source.geometry;

  // SEG: one frame per slice at that slice's own position; read back by soiq and by pydicom.
  SegSegment segment;
  segment.label = "ELLIPSOID";
  segment.volume = study.structure->volume;
  auto seg = write_seg(study.source, {segment});
  ASSERT_TRUE(seg.ok()) << seg.status().to_string();
  const std::string seg_path = tmp.file("seg.dcm.out");
  std::ofstream(seg_path, std::ios::binary) << seg->bytes;
  auto read = read_seg_file(seg_path, g);
  ASSERT_TRUE(read.ok()) << read.status().to_string();
  EXPECT_EQ(differing(read->segments.at(0).volume, study.structure->volume, stack.name + " SEG, soiq"), 0);
  const std::vector<Mask> by_pydicom = testing::pydicom_segments(seg_path, g, 1, tmp);
  ASSERT_EQ(by_pydicom.size(), 1u);
  EXPECT_EQ(differing(from_mask(by_pydicom[0]), study.structure->volume, stack.name + " SEG, pydicom"), 0);

  // RT Structure Set cut from the structure's surface on each plane: pydicom's fill from the
  // slices' own positions equals the 1D method on the series' grid, and soiq reads it back.
  auto v = voxelize_1d(study.structure->surface, g);
  ASSERT_TRUE(v.ok()) << v.status().to_string();
  EXPECT_EQ(differing(v->volume, study.structure->volume, stack.name + " surface -> 1D vs import"), 0);
  auto sections = slice_sections(study.structure->surface, g, "ELLIPSOID");
  ASSERT_TRUE(sections.ok()) << sections.status().to_string();
  RtStructRoi roi;
  roi.name = "ELLIPSOID";
  roi.contours = std::move(*sections);
  auto rt = write_rt_struct(study.source, {roi});
  ASSERT_TRUE(rt.ok()) << rt.status().to_string();
  const std::string rt_path = tmp.file("exported_rtstruct.dcm.out");
  std::ofstream(rt_path, std::ios::binary) << rt->bytes;
  EXPECT_EQ(differing(pydicom_reading(rt_path, tmp.path(), g, tmp), v->volume, stack.name + " RTSTRUCT out, pydicom"),
            0);
  auto rs = read_rt_struct(rt_path);
  ASSERT_TRUE(rs.ok()) << rs.status().to_string();
  auto back = convert_rt_struct(*rs, g);
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  ASSERT_EQ(back->structures.size(), 1u);
  EXPECT_EQ(differing(back->structures[0].volume, v->volume, stack.name + " RTSTRUCT out, soiq"), 0);
}

INSTANTIATE_TEST_SUITE_P(Synthetic, IrregularStack, ::testing::ValuesIn(stacks()), [](const auto& info) {
  return std::string(info.param.tilted ? "Tilted" : "") + (info.param.uneven ? "Uneven" : "");
});

// STS_002's CT altered by altered_series.py as a new series: resampled onto a sheared stack (each
// slice's first pixel k x (0.37, 0.21) pixels further, its pixels interpolated there), thinned
// through the tumour (every other slice of 10..30 left out, with the contours on them), or both.
// The real RT Structure Set's other contours still lie on the planes, and fall on other voxel
// centres.
struct Alteration {
  std::string name, args;
  bool tilted, uneven;
};

void PrintTo(const Alteration& a, std::ostream* os) { *os << a.name; }

class AlteredSts : public ::testing::TestWithParam<Alteration> {};

TEST_P(AlteredSts, ImportEqualsPydicomsFillFromEachSlicesOwnPosition) {
  const Alteration& alteration = GetParam();
  const std::string python = testing::python_with_pydicom();
  ASSERT_FALSE(python.empty()) << "no python3 with pydicom and numpy (scripts/install-deps)";
  TempDir tmp;
  const std::string ct = data_dir("sts/STS_002/dicom/CT");
  const std::string image = tmp.file("image");
  int status = 0;
  const std::string said = testing::run_command(python + " " + data_dir("../dicom/altered_series.py") + " " + ct +
                                                    "/image " + image + " " + alteration.args + " " + ct + "/mask",
                                                status);
  ASSERT_EQ(status, 0) << said;
  const Imported study = import_study({image});
  ASSERT_NE(study.structure, nullptr);
  const ImageGeometry& g = study.source.geometry;
  EXPECT_EQ(g.sheared(), alteration.tilted) << describe(g);
  EXPECT_EQ(g.uneven(), alteration.uneven) << describe(g);
  std::cout << "STS_002 CT " << alteration.name << ": " << describe(g)
            << " (altered_series.py: " << said.substr(0, said.find('\n')) << ")\n";
  const RunLengthVolume oracle = pydicom_reading(image + "/RS.dcm", image, g, tmp);
  EXPECT_EQ(
      differing(study.structure->volume, oracle, "STS_002 GTV on the " + alteration.name + " CT, import vs pydicom"),
      0);
}

INSTANTIATE_TEST_SUITE_P(Sts002, AlteredSts,
                         ::testing::Values(Alteration{"sheared", "--shear 0.37 0.21", true, false},
                                           Alteration{"thinned", "--thin 10 30", false, true},
                                           Alteration{"sheared and thinned", "--shear 0.37 0.21 --thin 10 30", true,
                                                      true}),
                         [](const auto& info) {
                           return std::string(info.param.tilted ? "Sheared" : "") +
                                  (info.param.uneven ? "Thinned" : "");
                         });

// Sheared, the tumour is the same as on the original stack to within a voxel layer.
TEST(AlteredStsVolume, ShearedGtvHasTheOriginalsVolume) {
  const std::string python = testing::python_with_pydicom();
  ASSERT_FALSE(python.empty());
  TempDir tmp;
  const std::string ct = data_dir("sts/STS_002/dicom/CT");
  int status = 0;
  const std::string said =
      testing::run_command(python + " " + data_dir("../dicom/altered_series.py") + " " + ct + "/image " +
                               tmp.file("image") + " --shear 0.37 0.21 " + ct + "/mask",
                           status);
  ASSERT_EQ(status, 0) << said;
  const Imported sheared = import_study({tmp.file("image")});
  const Imported original = import_study({ct});
  ASSERT_NE(sheared.structure, nullptr);
  ASSERT_NE(original.structure, nullptr);
  const double sheared_mm3 =
      double(voxel_count(sheared.structure->volume)) * sheared.source.geometry.voxel_volume_mm3();
  const double original_mm3 =
      double(voxel_count(original.structure->volume)) * original.source.geometry.voxel_volume_mm3();
  std::cout << "STS_002 GTV: " << sheared_mm3 << " mm3 on the sheared CT, " << original_mm3 << " on the original\n";
  EXPECT_NEAR(sheared_mm3, original_mm3, 0.02 * original_mm3);
}

}  // namespace irregular_stacks_test
}  // namespace soiq::dicom
