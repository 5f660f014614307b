// The kernels dispatched by CPU level (core/base/cpu_dispatch.h) give the same outputs, bit for bit,
// at every level this CPU runs: the same voxels, the same coverage fractions, every feature to the
// last bit. Each level is forced
// with cap_cpu_level and compared with the baseline (x86-64) run.
#include "core/base/cpu_level.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/base/coverage_volume.h"
#include "core/features/feature_catalogue.h"
#include "core/features/structure_features.h"
#include "core/geometry/primitives.h"
#include "core/voxelize/coverage_1d.h"
#include "core/voxelize/voxelize_1d.h"

namespace soiq {
namespace {

constexpr CpuLevel kLevels[] = {CpuLevel::kBaseline, CpuLevel::kV2, CpuLevel::kV3};

// Restores the CPU's own level however a test ends.
struct UncapAtEnd {
  ~UncapAtEnd() { cap_cpu_level(std::nullopt); }
};

TEST(CpuLevelTest, NamesAreMarchsAndRoundTrip) {
  EXPECT_EQ(cpu_level_name(CpuLevel::kBaseline), "x86-64");
  EXPECT_EQ(cpu_level_name(CpuLevel::kV2), "x86-64-v2");
  EXPECT_EQ(cpu_level_name(CpuLevel::kV3), "x86-64-v3");
  for (const CpuLevel l : kLevels) EXPECT_EQ(parse_cpu_level(cpu_level_name(l)), l);
  EXPECT_EQ(parse_cpu_level("x86-64-v4"), std::nullopt);
  EXPECT_EQ(parse_cpu_level("avx2"), std::nullopt);
}

TEST(CpuLevelTest, ACapLowersTheLevelAndNeverRaisesIt) {
  UncapAtEnd uncap;
  const CpuLevel detected = detected_cpu_level();
  EXPECT_EQ(cpu_level(), detected);
  cap_cpu_level(CpuLevel::kBaseline);
  EXPECT_EQ(cpu_level(), CpuLevel::kBaseline);
  cap_cpu_level(CpuLevel::kV3);
  EXPECT_EQ(cpu_level(), detected);  // at most what the CPU runs
  cap_cpu_level(std::nullopt);
  EXPECT_EQ(cpu_level(), detected);
}

// Runs `f` at every level this CPU runs and expects each result to equal the baseline's.
template <typename T>
void expect_same_at_every_level(const std::function<T()>& f, const std::string& what) {
  UncapAtEnd uncap;
  cap_cpu_level(CpuLevel::kBaseline);
  const T baseline = f();
  int compared = 0;
  for (const CpuLevel l : kLevels) {
    if (l == CpuLevel::kBaseline || int(l) > int(detected_cpu_level())) continue;
    cap_cpu_level(l);
    EXPECT_TRUE(f() == baseline) << what << " differs at " << cpu_level_name(l);
    ++compared;
  }
  if (compared == 0) GTEST_SKIP() << "this CPU runs x86-64 only: no other level to compare";
}

// An oblique, anisotropic grid around a mesh, so that no coordinate is a round number.
ImageGeometry oblique_grid(std::array<int64_t, 3> dims) {
  ImageGeometry g;
  g.dims = dims;
  g.spacing_mm = {0.83, 0.91, 1.37};
  g.direction = rotation_about({0.3, -0.5, 0.8}, 0.41);
  g.origin_mm = {-26.1, -27.3, -25.9};
  return g;
}

struct Runs {
  std::vector<int64_t> line_start;
  std::vector<Run> runs;
  bool operator==(const Runs&) const = default;
};

Runs convert(const TriangleMesh& mesh, const ImageGeometry& g, int threads, bool robust) {
  VoxelizeOptions o;
  o.threads = threads;
  o.robust = robust;
  Result<Voxelization> v = voxelize_1d(mesh, g, o);
  EXPECT_TRUE(v.ok()) << v.status().to_string();
  if (!v.ok()) return {};
  return {v->volume.line_start, v->volume.runs};
}

TEST(CpuLevelTest, TheOneDMethodGivesTheSameVoxelsAtEveryLevel) {
  const TriangleMesh sphere = uv_sphere_with_triangles({0.4, -0.7, 1.1}, 19.3, 60000);
  const TriangleMesh ring = torus({-1.3, 0.6, 0.2}, 14.1, 5.2, 90, 40);
  const ImageGeometry g = oblique_grid({64, 60, 40});
  for (const int threads : {1, 2}) {
    expect_same_at_every_level<Runs>([&] { return convert(sphere, g, threads, false); },
                                     "sphere, threads " + std::to_string(threads));
    expect_same_at_every_level<Runs>([&] { return convert(ring, g, threads, false); },
                                     "torus, threads " + std::to_string(threads));
  }
  // Robust mode scans along all three axes; an open surface (a triangle gone) abstains on lines.
  TriangleMesh open = sphere;
  open.triangles.pop_back();
  expect_same_at_every_level<Runs>([&] { return convert(open, g, 1, true); }, "open sphere, robust");
  // An unevenly spaced grid: each slice's rows at their own z.
  ImageGeometry uneven = oblique_grid({64, 60, 5});
  uneven.slice_positions_mm = {0, 1.1, 7.4, 9.9, 19.0};
  uneven.spacing_mm[2] = 19.0 / 4;
  uneven.origin_mm = {-26.1, -27.3, -8.9};
  ASSERT_GT(convert(sphere, uneven, 1, false).runs.size(), 100u);  // the grid does cut the sphere
  expect_same_at_every_level<Runs>([&] { return convert(sphere, uneven, 1, false); }, "sphere, uneven grid");
}

struct Fractions {
  std::vector<int64_t> full_start, partial_start;
  std::vector<Run> full;
  std::vector<PartialVoxel> partial;
  bool operator==(const Fractions&) const = default;
};

TEST(CpuLevelTest, CoverageFractionsAreTheSameAtEveryLevel) {
  const TriangleMesh sphere = uv_sphere_with_triangles({0.4, -0.7, 1.1}, 19.3, 20000);
  const ImageGeometry g = oblique_grid({64, 60, 40});
  for (const int n : {1, 4}) {
    expect_same_at_every_level<Fractions>(
        [&] {
          CoverageOptions o;
          o.lines_per_voxel = n;
          o.threads = 2;
          Result<CoverageVolume> c = coverage_1d(sphere, g, o);
          EXPECT_TRUE(c.ok()) << c.status().to_string();
          if (!c.ok()) return Fractions{};
          return Fractions{c->full_start, c->partial_start, c->full, c->partial};
        },
        "coverage n=" + std::to_string(n));
  }
}

// Every feature soiq reports, as (name, region, image, the value's bits): NaN equals NaN here, and
// -0 differs from +0, so "the same" is to the last bit.
struct Report {
  std::vector<std::string> keys;
  std::vector<std::vector<uint64_t>> bits;
  bool operator==(const Report&) const = default;
};

Report report(const Result<FeatureReport>& r) {
  EXPECT_TRUE(r.ok()) << r.status().to_string();
  Report out;
  if (!r.ok()) return out;
  for (const Feature& f : r->features) {
    out.keys.push_back(f.name + "/" + f.region + "/" + f.image);
    std::vector<uint64_t> b(f.value.size());
    std::memcpy(b.data(), f.value.data(), b.size() * sizeof(uint64_t));
    out.bits.push_back(std::move(b));
  }
  return out;
}

TEST(CpuLevelTest, EveryFeatureIsTheSameAtEveryLevel) {
  const TriangleMesh sphere = uv_sphere_with_triangles({0.4, -0.7, 1.1}, 15.3, 20000);
  const ImageGeometry g = oblique_grid({64, 60, 40});
  const Result<Voxelization> v = voxelize_1d(sphere, g);
  ASSERT_TRUE(v.ok()) << v.status().to_string();
  Image ramp;
  ramp.geometry = g;
  ramp.voxels.resize(size_t(g.voxel_count()));
  for (size_t i = 0; i < ramp.voxels.size(); ++i) ramp.voxels[i] = float(std::sin(0.001 * double(i)) * 100 + 0.37 * i);
  const StructureInput input{v->volume, std::make_shared<const TriangleMesh>(sphere)};
  for (const Interpolation interpolation : {Interpolation::kNearest, Interpolation::kLinear}) {
    FeatureRequest request;  // every name
    request.images = {{"ramp", &ramp}};
    request.regions = {RegionSpec{}, RegionSpec{RegionKind::kShell, 3}, RegionSpec{RegionKind::kCore, 2}};
    request.interpolation = interpolation;
    request.threads = 2;
    expect_same_at_every_level<Report>([&] { return report(structure_features(input, request)); },
                                       std::string("features, ") + interpolation_name(interpolation));
    FeatureRequest weighted;
    weighted.names = weighted_feature_names();
    weighted.images = {{"ramp", &ramp}};
    weighted.interpolation = interpolation;
    expect_same_at_every_level<Report>([&] { return report(structure_features(input, weighted)); },
                                       std::string("weighted features, ") + interpolation_name(interpolation));
  }
}

}  // namespace
}  // namespace soiq
