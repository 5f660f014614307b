#include "core/voxelize/memory_estimate.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

#include "core/geometry/primitives.h"
#include "core/voxelize/coverage_1d.h"
#include "core/voxelize/grid_around.h"
#include "core/voxelize/voxelize_1d.h"
#include "tests/support/address_sanitizer.h"

namespace soiq {
namespace {

// An axis-aligned box from (0,0,0) to `size`, closed and outward.
TriangleMesh box(const Vec3& size) {
  TriangleMesh m;
  for (int v = 0; v < 8; ++v) m.vertices_mm.push_back({v & 1 ? size[0] : 0, v & 2 ? size[1] : 0, v & 4 ? size[2] : 0});
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

// The crossing bound is a bound: each run of the real conversion starts and ends at a crossing.
TEST(MemoryEstimate, CrossingsBoundTheRunsOfTheRealConversion) {
  for (const double spacing : {2.0, 1.0, 0.37}) {
    for (const TriangleMesh& mesh : {uv_sphere({1, 2, 3}, 20, 24, 48), box({7.3, 30.1, 12.9})}) {
      const auto grid = grid_around(mesh, {spacing, spacing, spacing}, 2);
      ASSERT_TRUE(grid.ok());
      const ConversionEstimate e = conversion_peak_bytes(mesh, *grid, false);
      const auto v = voxelize_1d(mesh, *grid, {});
      ASSERT_TRUE(v.ok()) << v.status().to_string();
      EXPECT_EQ(e.lines, grid->dims[1] * grid->dims[2]);
      EXPECT_LE(2 * int64_t(v->volume.runs.size()), e.crossings) << spacing;
      // An oblique grid (rotated 30 degrees about z, then 20 about x): the bound ignores orientation.
      ImageGeometry oblique = *grid;
      const double c1 = std::cos(0.5236), s1 = std::sin(0.5236), c2 = std::cos(0.349), s2 = std::sin(0.349);
      oblique.direction = {{{c1, -s1 * c2, s1 * s2}, {s1, c1 * c2, -c1 * s2}, {0, s2, c2}}};
      const auto w = voxelize_1d(mesh, oblique, {});
      ASSERT_TRUE(w.ok()) << w.status().to_string();
      EXPECT_GT(w->volume.runs.size(), 0u);
      EXPECT_LE(2 * int64_t(w->volume.runs.size()), conversion_peak_bytes(mesh, oblique, false).crossings);
    }
  }
}

// Peaks measured on this project's reference machine with
//   /usr/bin/time -f %M soiq features MESH --spacing S [--margin 0] --features voxel_count
// minus ~30 MB of process baseline: the estimate must not be below them. The slab is the memory
// bomb (2.5 x 12000 x 12000 mm at 1 mm: 4 x 12001 x 12001 voxels, 15.6 GB measured).
TEST(MemoryEstimate, IsAboveTheMeasuredPeaks) {
  const TriangleMesh slab = box({2.5, 12000, 12000});
  const auto slab_grid = grid_around(slab, {1, 1, 1}, 0);
  ASSERT_TRUE(slab_grid.ok());
  const ConversionEstimate e = conversion_peak_bytes(slab, *slab_grid, false);
  EXPECT_GE(e.bytes, int64_t(15'600'000'000));
  EXPECT_LE(e.bytes, int64_t(30'000'000'000));  // and not absurdly above: it must still admit real work

  const TriangleMesh sphere = uv_sphere({0, 0, 0}, 100, 64, 128);
  for (const auto& [spacing, measured] : {std::pair{0.5, int64_t(67'000'000)}, std::pair{0.3, int64_t(162'000'000)}}) {
    const auto grid = grid_around(sphere, {spacing, spacing, spacing}, 2);
    ASSERT_TRUE(grid.ok());
    const ConversionEstimate c = conversion_peak_bytes(sphere, *grid, false);
    EXPECT_GE(c.bytes + features_extra_bytes(c, *grid, 0, 0), measured) << spacing;
  }
}

TEST(MemoryEstimate, AbsurdMeshesSaturateInsteadOfOverflowing) {
  const TriangleMesh huge = box({1e12, 1e12, 1e12});
  ImageGeometry g;
  g.dims = {1'000'000'000, 1'000'000'000, 1'000'000'000};
  const ConversionEstimate e = conversion_peak_bytes(huge, g, true);
  EXPECT_EQ(e.bytes, std::numeric_limits<int64_t>::max());
  EXPECT_EQ(features_extra_bytes(e, g, std::numeric_limits<int64_t>::max(), 3), std::numeric_limits<int64_t>::max());
}

TEST(MemoryEstimate, ByteSizesAreReadAndWrittenAsPeopleDo) {
  EXPECT_EQ(*parse_byte_size("8G", "x"), int64_t(8) << 30);
  EXPECT_EQ(*parse_byte_size("512MiB", "x"), int64_t(512) << 20);
  EXPECT_EQ(*parse_byte_size("64k", "x"), int64_t(64) << 10);
  EXPECT_EQ(*parse_byte_size("1234", "x"), 1234);
  for (const char* bad : {"", "G", "-1G", "1.5G", "lots", "99999999999T"}) {
    auto r = parse_byte_size(bad, "--memory-budget");
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(r.status().message().find("--memory-budget"), std::string::npos);
  }
  EXPECT_EQ(human_bytes(999), "999 bytes");
  EXPECT_EQ(human_bytes(15'600'000'000), "15.6 GB");
  EXPECT_EQ(human_bytes(int64_t(1) << 30), "1.07 GB");
  EXPECT_GT(default_memory_budget_bytes(), 0);
}

// Under ulimit -v (RLIMIT_AS) or ulimit -d (RLIMIT_DATA) the default budget is what that limit has
// left, halved: work admitted past it would fail to allocate instead of queueing. Measured in a
// child, whose limit goes with it. `statm_field` is the limit's counter in /proc/self/statm (0 the
// whole address space, 5 data + stack).
void expect_budget_within_limit(int resource, int statm_field) {
  const int64_t unlimited = default_memory_budget_bytes();
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    int64_t fields[6] = {0, 0, 0, 0, 0, 0};
    std::ifstream statm("/proc/self/statm");
    for (int64_t& f : fields) statm >> f;
    const int64_t in_use = fields[statm_field] * sysconf(_SC_PAGE_SIZE);
    const rlimit limit{rlim_t(in_use + (int64_t(3) << 30)), rlim_t(in_use + (int64_t(3) << 30))};
    int64_t budget = -1;
    if (setrlimit(resource, &limit) == 0) budget = default_memory_budget_bytes();
    const int64_t out[2] = {budget, in_use};
    (void)!write(fds[1], out, sizeof out);
    _exit(0);
  }
  close(fds[1]);
  int64_t got[2] = {0, 0};
  ASSERT_EQ(read(fds[0], got, sizeof got), ssize_t(sizeof got));
  close(fds[0]);
  waitpid(child, nullptr, 0);
  ASSERT_GT(got[0], 0) << "setrlimit failed in the child";
  // 3 GiB left, less 1.1 GiB for the threads to come, halved: about 0.94 GiB, whatever the RAM.
  EXPECT_LE(got[0], (int64_t(3) << 30) / 2);
  EXPECT_GE(got[0], int64_t(900) << 20);
  EXPECT_LE(got[0], unlimited);
}

TEST(MemoryEstimate, TheDefaultBudgetRespectsTheProcessAddressSpaceLimit) { expect_budget_within_limit(RLIMIT_AS, 0); }

TEST(MemoryEstimate, TheDefaultBudgetRespectsTheProcessDataLimit) { expect_budget_within_limit(RLIMIT_DATA, 5); }

// The growth of resident memory while `work` runs in a child process, from a reset high-water mark
// (Linux: writing 5 to /proc/self/clear_refs resets VmHWM); -1 where that is not possible.
int64_t child_peak_growth(const std::function<void()>& work) {
  int fds[2];
  if (pipe(fds) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    auto status_kb = [](const char* key) {
      std::ifstream in("/proc/self/status");
      std::string word;
      while (in >> word) {
        if (word == key) {
          int64_t kb = 0;
          in >> kb;
          return kb;
        }
      }
      return int64_t(-1);
    };
    int64_t growth = -1;
    std::ofstream reset("/proc/self/clear_refs");
    if (reset << "5" << std::flush) {
      reset.close();
      const int64_t before = status_kb("VmRSS:");
      work();
      growth = (status_kb("VmHWM:") - before) * 1024;
    }
    (void)!write(fds[1], &growth, sizeof growth);
    _exit(0);
  }
  close(fds[1]);
  int64_t growth = -1;
  if (read(fds[0], &growth, sizeof growth) != sizeof growth) growth = -1;
  close(fds[0]);
  waitpid(pid, nullptr, 0);
  return growth;
}

// Coverage fractions: the estimate is above what the result holds and above the measured growth,
// for a sphere, a thin disc lying within one voxel slice (all its crossings in one slice, every
// voxel of it partly covered) and a bar along the rows, at 1 to 8 lines per voxel side.
TEST(MemoryEstimate, CoverageEstimateIsAboveWhatItHoldsAndItsPeak) {
  const std::vector<std::pair<const char*, TriangleMesh>> meshes = {
      {"sphere", uv_sphere({1, 2, 3}, 40, 64, 128)},
      {"disc", box({300, 300, 0.4})},
      {"bar", box({400, 0.6, 0.6})},
  };
  for (const auto& named : meshes) {
    // Not a structured binding: clang 14 refuses to capture one in the lambda below.
    const char* name = named.first;
    const TriangleMesh& mesh = named.second;
    auto grid = grid_around(mesh, {1, 1, 1}, 2);
    ASSERT_TRUE(grid.ok());
    // Centre the disc and the bar on voxel centres' planes (a slice, a line of rows).
    grid->origin_mm = grid->origin_mm + Vec3{0, std::string(name) == "bar" ? 0.3 - 2.0 : 0.0, 0.2 - 2.0};
    for (int n : {1, 4, 8}) {
      const ConversionEstimate e = coverage_peak_bytes(surface_measure(mesh), *grid, n);
      CoverageOptions o;
      o.lines_per_voxel = n;
      const auto v = coverage_1d(mesh, *grid, o);
      ASSERT_TRUE(v.ok()) << v.status().to_string();
      EXPECT_GT(v->partial.size(), 0u) << name;
      EXPECT_LE(coverage_bytes(*v), e.bytes) << name << " n=" << n;
      const int64_t peak = child_peak_growth([&] { (void)coverage_1d(mesh, *grid, o); });
      std::printf("%-6s n=%d: estimate %s, held %s, peak growth %s\n", name, n, human_bytes(e.bytes).c_str(),
                  human_bytes(coverage_bytes(*v)).c_str(), peak < 0 ? "?" : human_bytes(peak).c_str());
      if (peak >= 0) {
        // Less what any work in the child adds (code pages, an allocator arena), measured for the
        // bar, whose conversion holds a few KB: 0.8-1.1 MB here, 2.5-2.8 MB under AddressSanitizer
        // (its allocator's regions and per-thread state), which a 2 MiB allowance failed now and then.
        const int64_t overhead = (SOIQ_TEST_UNDER_ASAN ? int64_t(4) : int64_t(2)) << 20;
        EXPECT_LE(peak - overhead, e.bytes) << name << " n=" << n;
      }
    }
  }
}

}  // namespace
}  // namespace soiq
