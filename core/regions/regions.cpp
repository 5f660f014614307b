#include "core/regions/regions.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/base/did_you_mean.h"
#include "core/regions/ball_morphology.h"
#include "core/regions/distance_transform.h"

namespace soiq {
namespace {

Status check_structure(const RunLengthVolume& v) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(v.geometry));
  const std::string bad = "structure's run table does not match its grid (" + describe(v.geometry) + ")";
  if (int64_t(v.line_start.size()) != v.line_count() + 1 || v.line_start.back() != int64_t(v.runs.size())) {
    return invalid_argument(bad);
  }
  for (const Run& run : v.runs) {
    if (run.begin < 0 || run.begin >= run.end || run.end > v.geometry.dims[0]) return invalid_argument(bad);
  }
  return ok_status();
}

// Runs of `a` minus runs of `b`, line by line (both on one grid).
RunLengthVolume subtract(const RunLengthVolume& a, const RunLengthVolume& b) {
  RunLengthVolume out;
  out.geometry = a.geometry;
  out.line_start.resize(a.line_start.size());
  for (int64_t l = 0; l < a.line_count(); ++l) {
    out.line_start[size_t(l)] = int64_t(out.runs.size());
    int64_t rb = b.line_start[size_t(l)];
    const int64_t eb = b.line_start[size_t(l) + 1];
    for (int64_t ra = a.line_start[size_t(l)]; ra < a.line_start[size_t(l) + 1]; ++ra) {
      int32_t from = a.runs[size_t(ra)].begin;
      const int32_t to = a.runs[size_t(ra)].end;
      while (rb < eb && b.runs[size_t(rb)].end <= from) ++rb;
      for (int64_t q = rb; q < eb && b.runs[size_t(q)].begin < to; ++q) {
        if (b.runs[size_t(q)].begin > from) out.runs.push_back({from, b.runs[size_t(q)].begin});
        from = std::max(from, b.runs[size_t(q)].end);
      }
      if (from < to) out.runs.push_back({from, to});
    }
  }
  out.line_start.back() = int64_t(out.runs.size());
  return out;
}

const char* kind_word(RegionKind kind) {
  switch (kind) {
    case RegionKind::kInside:
      return "inside";
    case RegionKind::kShell:
      return "shell";
    case RegionKind::kCore:
      return "core";
  }
  return "?";
}

}  // namespace

Result<RegionSpec> parse_region(std::string_view text) {
  const std::string accepted = "; expected inside, shell:R or core:R with R in mm > 0 (e.g. shell:5)";
  if (text == "inside") return RegionSpec{RegionKind::kInside, 0};
  RegionSpec spec;
  std::string_view number;
  if (text.starts_with("shell:")) {
    spec.kind = RegionKind::kShell;
    number = text.substr(6);
  } else if (text.starts_with("core:")) {
    spec.kind = RegionKind::kCore;
    number = text.substr(5);
  } else {
    // Suggest with the reader's own radius: "shel:5" means "shell:5", not "shell:R".
    const size_t colon = text.find(':');
    const std::string radius = colon == std::string_view::npos ? "R" : std::string(text.substr(colon + 1));
    const std::string names[] = {"inside", "shell:" + radius, "core:" + radius};
    return invalid_argument("unknown region '" + std::string(text) + "'" + did_you_mean(text, names) + accepted);
  }
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), spec.radius_mm);
  if (ec != std::errc() || end != number.data() + number.size() || !std::isfinite(spec.radius_mm) ||
      !(spec.radius_mm > 0)) {
    return invalid_argument("region '" + std::string(text) + "' has no valid radius" + accepted);
  }
  return spec;
}

std::string region_name(const RegionSpec& spec) {
  if (spec.kind == RegionKind::kInside) return "inside";
  // The shortest text that reads back to the same radius: region names key soiqd's feature cache
  // and label rows, so two radii must never print alike (%g made shell:1.0000001 "shell:1").
  char digits[32];
  const auto end = std::to_chars(digits, digits + sizeof digits, spec.radius_mm).ptr;
  return std::string(kind_word(spec.kind)) + ":" + std::string(digits, end);
}

namespace {

// What both region() and cheapest_region_method() work out before building anything.
struct RegionPlan {
  double r = 0;         // the radius, clamped to what the grid can tell apart
  VoxelBox inside_box;  // of the structure
  VoxelBox box;         // grown by r, clipped to the grid
  RegionMethod cheapest = RegionMethod::kRuns;
};

Result<RegionPlan> plan_region(const RunLengthVolume& structure, const RegionSpec& spec) {
  SOIQ_RETURN_IF_ERROR(check_structure(structure));
  RegionPlan plan;
  if (spec.kind == RegionKind::kInside) return plan;
  if (!std::isfinite(spec.radius_mm) || !(spec.radius_mm > 0)) {
    return invalid_argument(std::string(kind_word(spec.kind)) + " radius must be a finite number of mm > 0, got " +
                            std::to_string(spec.radius_mm));
  }
  const ImageGeometry& g = structure.geometry;
  if (g.sheared() || g.uneven()) {
    // Balls and distance transforms here walk the grid's axes as if at right angles and evenly
    // spaced.
    return failed_precondition(std::string(kind_word(spec.kind)) +
                               " regions measure distances along the grid's axes, which are not at right angles or "
                               "evenly spaced on a gantry-tilted or unevenly spaced series; use the inside region "
                               "there, or a grid of your own (--spacing) for the structure");
  }
  plan.inside_box = voxel_box(structure);
  if (plan.inside_box.empty) return plan;
  // No two voxel centres of the grid are farther apart than its diagonal: a larger radius selects
  // exactly what twice the diagonal does, and r * r then stays finite.
  double diagonal2 = 0;
  for (int a = 0; a < 3; ++a) diagonal2 += std::pow(double(g.dims[size_t(a)]) * g.spacing_mm[size_t(a)], 2);
  plan.r = std::min(spec.radius_mm, 2 * std::sqrt(diagonal2));

  // Every voxel within r mm of an inside voxel (shell), and every outside voxel within r mm of an
  // inside one (core), lies in the inside box grown by ceil(r / spacing) along each axis. The factor
  // covers the tie tolerance.
  plan.box = plan.inside_box;
  for (int a = 0; a < 3; ++a) {
    const double grow = std::ceil(plan.r / g.spacing_mm[size_t(a)] * (1 + 1e-9));
    const int64_t n = g.dims[size_t(a)];
    const int64_t margin = grow >= double(n) ? n : int64_t(grow);
    plan.box.lo[size_t(a)] = std::max<int64_t>(0, plan.box.lo[size_t(a)] - margin);
    plan.box.hi[size_t(a)] = std::min<int64_t>(n - 1, plan.box.hi[size_t(a)] + margin);
  }

  // On the runs when the ball's (j, k) cross section times the runs per line costs less than the
  // transform's pass over the box. Per line of the box, measured on SM1 (1 mm, one thread): the
  // runs cost ~2.7 ns per offset line and run, the transform ~20 ns per voxel, so the break-even is
  // at ~7 offsets per box voxel along i (shell and core of 10 mm: 10 and 7 ms on the runs against
  // 24 and 25 ms by the transform; 20 mm: 37 against 24 ms). 6 leans to the transform.
  const int64_t lines = std::max<int64_t>(1, plan.inside_box.dims()[1] * plan.inside_box.dims()[2]);
  const double runs_per_line = double(structure.runs.size()) / double(lines);
  const double budget = 6.0 * double(plan.box.dims()[0]) / std::max(1.0, runs_per_line);  // offset lines
  const int64_t stop_at = int64_t(std::min(budget, 1e9)) + 1;
  plan.cheapest =
      double(ball_offset_lines(g, plan.r, stop_at)) < budget ? RegionMethod::kRuns : RegionMethod::kTransform;
  return plan;
}

}  // namespace

Result<RegionMethod> cheapest_region_method(const RunLengthVolume& structure, const RegionSpec& spec) {
  SOIQ_ASSIGN_OR_RETURN(const RegionPlan plan, plan_region(structure, spec));
  return plan.cheapest;
}

Result<RunLengthVolume> region(const RunLengthVolume& structure, const RegionSpec& spec, const RegionOptions& options) {
  SOIQ_ASSIGN_OR_RETURN(const RegionPlan plan, plan_region(structure, spec));
  if (spec.kind == RegionKind::kInside) return structure;
  const ImageGeometry& g = structure.geometry;
  if (plan.inside_box.empty) return empty_volume(g);
  const double r = plan.r;
  const VoxelBox& box = plan.box;
  const std::array<int64_t, 3> bd = box.dims();
  if (double(bd[0]) * double(bd[1]) * double(bd[2]) > double(options.max_box_voxels)) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%s: the structure's bounding box grown by %g mm has %lldx%lldx%lld voxels, over the limit of %lld; "
                  "use a smaller radius or a coarser grid",
                  region_name(spec).c_str(), spec.radius_mm, (long long)bd[0], (long long)bd[1], (long long)bd[2],
                  (long long)options.max_box_voxels);
    return resource_exhausted(buf);
  }
  const bool is_shell = spec.kind == RegionKind::kShell;
  const RegionMethod method = options.method == RegionMethod::kCheapest ? plan.cheapest : options.method;
  if (method == RegionMethod::kRuns) {
    return is_shell ? subtract(ball_dilation(structure, r), structure) : ball_erosion(structure, r);
  }

  // Dense inside flags of the box.
  const int64_t ny = g.dims[1];
  std::vector<uint8_t> inside = box_mask(structure, box);

  // Shell: distances to the inside voxels; core: to the outside ones.
  std::vector<uint8_t> outside;
  if (!is_shell) {
    outside.resize(inside.size());
    for (size_t n = 0; n < inside.size(); ++n) outside[n] = uint8_t(inside[n] ^ 1);
  }
  SOIQ_ASSIGN_OR_RETURN(
      const std::vector<double> d2,
      squared_distance_transform(is_shell ? inside : outside, bd, g.spacing_mm, std::max(options.threads, 1)));
  outside = {};

  // The tie tolerance: d2 is a sum of at most three rounded squares, r*r one rounded square.
  const double r2 = r * r * (1 + 1e-12);
  RunLengthVolume out;
  out.geometry = g;
  out.line_start.resize(size_t(structure.line_count()) + 1);
  for (int64_t l = 0; l < structure.line_count(); ++l) {
    out.line_start[size_t(l)] = int64_t(out.runs.size());
    const int64_t j = l % ny, k = l / ny;
    if (j < box.lo[1] || j > box.hi[1] || k < box.lo[2] || k > box.hi[2]) continue;
    const size_t row = size_t(bd[0] * ((j - box.lo[1]) + bd[1] * (k - box.lo[2])));
    int64_t begin = -1;
    for (int64_t i = 0; i <= bd[0]; ++i) {
      bool selected = false;
      if (i < bd[0]) {
        const bool in = inside[row + size_t(i)] != 0;
        const double d = d2[row + size_t(i)];
        selected = is_shell ? (!in && d <= r2) : (in && d > r2);
      }
      if (selected && begin < 0) begin = i;
      if (!selected && begin >= 0) {
        out.runs.push_back({int32_t(begin + box.lo[0]), int32_t(i + box.lo[0])});
        begin = -1;
      }
    }
  }
  out.line_start.back() = int64_t(out.runs.size());
  return out;
}

}  // namespace soiq
