#include "dicom/slice_stack.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace soiq::dicom {
namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

std::string fmt(const Vec3& p) { return "(" + fmt(p[0]) + ", " + fmt(p[1]) + ", " + fmt(p[2]) + ")"; }

std::string fmt_orientation(const std::array<double, 6>& o) {
  std::string out;
  for (int i = 0; i < 6; ++i) out += (i ? "\\" : "") + fmt(o[i]);
  return out;
}

bool near(double a, double b, double tol) { return std::abs(a - b) <= tol; }

// Beyond any scanner: a pixel of a metre, a position a kilometre from the origin. Bounded so that
// every distance computed from them stays far from overflow.
constexpr double kMaxPixelSpacingMm = 1e3;
constexpr double kMaxPositionMm = 1e6;

// Checks every number one slice brings before any is used: a NaN position would break the sort's
// ordering and pass every distance test below (NaN compares false), an infinite spacing would
// pass "> 0".
Status check_slice_values(const SliceInfo& s) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(s.position_mm[a]) || std::abs(s.position_mm[a]) > kMaxPositionMm)
      return invalid_argument("slice " + s.label + ": Image Position (Patient) (0020,0032) " + fmt(s.position_mm) +
                              " is not a finite position within " + fmt(kMaxPositionMm) + " mm; fix the tag");
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(s.orientation[i]))
      return invalid_argument("slice " + s.label + ": Image Orientation (Patient) (0020,0037) " +
                              fmt_orientation(s.orientation) + " is not finite; fix the tag");
  for (int i = 0; i < 2; ++i)
    if (!(s.pixel_spacing_mm[i] > 0) || !(s.pixel_spacing_mm[i] <= kMaxPixelSpacingMm))
      return invalid_argument("slice " + s.label + ": Pixel Spacing (0028,0030) " + fmt(s.pixel_spacing_mm[0]) + "\\" +
                              fmt(s.pixel_spacing_mm[1]) + " must be finite, > 0 and at most " +
                              fmt(kMaxPixelSpacingMm) + " mm; fix the tag");
  if (s.rows <= 0 || s.columns <= 0)
    return invalid_argument("slice " + s.label + ": Rows (0028,0010) " + std::to_string(s.rows) +
                            " and Columns (0028,0011) " + std::to_string(s.columns) + " must be positive");
  return ok_status();
}

// Checks that the first slice's row and column directions are orthonormal: the grid's direction
// matrix is built from them, and every other slice is compared with this one.
Status check_orthonormal(const SliceInfo& first, const Vec3& row, const Vec3& col) {
  if (!near(norm(row), 1, 1e-4) || !near(norm(col), 1, 1e-4) || std::abs(dot(row, col)) > 1e-4)
    return invalid_argument("slice " + first.label + ": Image Orientation (Patient) (0020,0037) " +
                            fmt_orientation(first.orientation) +
                            " is not two orthonormal vectors (unit length and perpendicular to 1e-4); fix the tag");
  return ok_status();
}

// Checks that a slice has the first slice's orientation, size and pixel spacing: one grid holds
// the whole series only if they agree.
Status check_same_as_first(const SliceInfo& s, const SliceInfo& first) {
  for (int i = 0; i < 6; ++i)
    if (!near(s.orientation[i], first.orientation[i], 1e-4))
      return invalid_argument("slice " + s.label +
                              " has a different Image Orientation (Patient) (0020,0037) than slice " + first.label +
                              "; a series must have one orientation");
  if (s.rows != first.rows || s.columns != first.columns)
    return invalid_argument("slice " + s.label + " is " + std::to_string(s.columns) + "x" + std::to_string(s.rows) +
                            ", slice " + first.label + " is " + std::to_string(first.columns) + "x" +
                            std::to_string(first.rows) + "; a series must have one size");
  for (int i = 0; i < 2; ++i)
    if (!near(s.pixel_spacing_mm[i], first.pixel_spacing_mm[i], 1e-6 * first.pixel_spacing_mm[i]))
      return invalid_argument("slice " + s.label + " has a different Pixel Spacing (0028,0030) than slice " +
                              first.label);
  return ok_status();
}

// Checks that consecutive slices (in `order`, sorted along n) are apart by more than `tol`.
Status check_distinct_positions(const std::vector<SliceInfo>& slices, const std::vector<size_t>& order,
                                const std::vector<double>& along, double tol) {
  for (size_t k = 0; k + 1 < slices.size(); ++k) {
    const SliceInfo& a = slices[order[k]];
    const SliceInfo& b = slices[order[k + 1]];
    if (along[order[k + 1]] - along[order[k]] <= tol)
      return invalid_argument("two slices at the same position: slices " + a.label + " at " + fmt(a.position_mm) +
                              " and " + b.label + " at " + fmt(b.position_mm));
  }
  return ok_status();
}

// True when some slice lies more than `tol` off the normal line through the first one: the stack
// is not along the normal of its planes (gantry tilt). Measured from the first slice, not from the
// previous one, so that a drift too small per step to see still counts once it adds up.
bool shifted_in_plane(const std::vector<SliceInfo>& slices, const std::vector<size_t>& order, const Vec3& n,
                      double tol) {
  const Vec3& first = slices[order.front()].position_mm;
  for (size_t k = 1; k < slices.size(); ++k) {
    const Vec3 d = slices[order[k]].position_mm - first;
    if (norm(d - dot(d, n) * n) > tol) return true;
  }
  return false;
}

// Checks that a tilted stack is tilted by one angle: every slice within `tol` of the line from the
// first slice to the last, at its own height along the normal, so one sheared grid holds all their
// voxel centres.
Status check_constant_tilt(const std::vector<SliceInfo>& slices, const std::vector<size_t>& order,
                           const std::vector<double>& along, const Vec3& n, const Vec3& k_axis, double tol) {
  const Vec3& first = slices[order.front()].position_mm;
  for (size_t k = 1; k < slices.size(); ++k) {
    const SliceInfo& s = slices[order[k]];
    const Vec3 expected = first + ((along[order[k]] - along[order[0]]) / dot(k_axis, n)) * k_axis;
    const double off = norm(s.position_mm - expected);
    if (off > tol)
      return invalid_argument("slice " + s.label + " at " + fmt(s.position_mm) + " is " + fmt(off) +
                              " mm from where one gantry tilt through the first and last slices puts it " +
                              fmt(expected) +
                              ": the slices are neither stacked along the normal of their planes "
                              "nor tilted by one angle");
  }
  return ok_status();
}

// True when every step between consecutive slices equals the smallest one (to max(0.01 mm, 1 %));
// false for an unevenly spaced stack, which a grid holds slice by slice. One pattern is refused: a
// step of about a whole multiple of the others with the smallest step on both sides, the trace of
// a file missing from a series, not of a protocol that changes its spacing (that runs longer).
Result<bool> steps_are_even(const std::vector<SliceInfo>& slices, const std::vector<size_t>& order,
                            const std::vector<double>& along) {
  const size_t steps = slices.size() - 1;
  std::vector<double> step(steps);
  for (size_t k = 0; k < steps; ++k) step[k] = along[order[k + 1]] - along[order[k]];
  const double smallest = *std::min_element(step.begin(), step.end());
  const double step_tol = std::max(0.01, 0.01 * smallest);
  auto even = [&](size_t k) { return near(step[k], smallest, step_tol); };
  bool all_even = true;
  for (size_t k = 0; k < steps; ++k) {
    if (even(k)) continue;
    all_even = false;
    const double ratio = step[k] / smallest;
    const double missing = std::round(ratio) - 1;
    const bool isolated = (k == 0 || even(k - 1)) && (k + 1 == steps || even(k + 1));
    if (missing >= 1 && near(ratio, std::round(ratio), 0.05) && isolated && steps >= 3) {
      const SliceInfo& a = slices[order[k]];
      const SliceInfo& b = slices[order[k + 1]];
      return invalid_argument(fmt(missing) + " missing slice(s) between " + a.label + " at " + fmt(a.position_mm) +
                              " and " + b.label + " at " + fmt(b.position_mm) + " (" + fmt(step[k]) +
                              " mm apart, the others " + fmt(smallest) + " mm): a file of the series is missing");
    }
  }
  return all_even;
}

}  // namespace

Result<StackGeometry> slice_stack(const std::vector<SliceInfo>& slices, double single_slice_spacing_mm) {
  if (slices.empty()) return invalid_argument("image series has no slices");
  for (const SliceInfo& s : slices) SOIQ_RETURN_IF_ERROR(check_slice_values(s));
  const SliceInfo& first = slices[0];
  const Vec3 row{first.orientation[0], first.orientation[1], first.orientation[2]};
  const Vec3 col{first.orientation[3], first.orientation[4], first.orientation[5]};
  SOIQ_RETURN_IF_ERROR(check_orthonormal(first, row, col));
  const Vec3 n = cross(row, col);
  for (const SliceInfo& s : slices) SOIQ_RETURN_IF_ERROR(check_same_as_first(s, first));

  // Slices in order along the normal; stable, so that slices at one position keep their input order.
  StackGeometry out;
  out.order.resize(slices.size());
  std::iota(out.order.begin(), out.order.end(), size_t{0});
  std::vector<double> along(slices.size());
  for (size_t i = 0; i < slices.size(); ++i) along[i] = dot(n, slices[i].position_mm);
  std::stable_sort(out.order.begin(), out.order.end(), [&](size_t a, size_t b) { return along[a] < along[b]; });

  Vec3 k_axis = n;
  double spacing =
      single_slice_spacing_mm > 0 && std::isfinite(single_slice_spacing_mm) ? single_slice_spacing_mm : 1.0;
  std::vector<double> positions;  // along k_axis from the first slice, for an uneven stack only
  if (slices.size() > 1) {
    const size_t last = out.order.back(), first_slice = out.order.front();
    spacing = (along[last] - along[first_slice]) / static_cast<double>(slices.size() - 1);
    const double tol = std::max(0.01, 0.01 * spacing);
    SOIQ_RETURN_IF_ERROR(check_distinct_positions(slices, out.order, along, tol));
    SOIQ_ASSIGN_OR_RETURN(const bool even, steps_are_even(slices, out.order, along));
    if (shifted_in_plane(slices, out.order, n, tol)) {
      // Gantry tilt: the grid's k axis runs from slice to slice, so its voxel centres are the slices'.
      const Vec3 span = slices[last].position_mm - slices[first_slice].position_mm;
      k_axis = (1.0 / norm(span)) * span;
      SOIQ_RETURN_IF_ERROR(check_constant_tilt(slices, out.order, along, n, k_axis, tol));
      spacing = norm(span) / static_cast<double>(slices.size() - 1);
    }
    if (!even) {
      // Each slice where it is along the k axis; the mean step is the grid's k spacing.
      for (const size_t i : out.order) positions.push_back((along[i] - along[first_slice]) / dot(k_axis, n));
      positions[0] = 0;
      spacing = positions.back() / static_cast<double>(slices.size() - 1);
    }
  }

  ImageGeometry& g = out.geometry;
  g.origin_mm = slices[out.order.front()].position_mm;
  g.spacing_mm = {first.pixel_spacing_mm[1], first.pixel_spacing_mm[0], spacing};
  g.dims = {first.columns, first.rows, static_cast<int64_t>(slices.size())};
  for (int r = 0; r < 3; ++r) g.direction[r] = {row[r], col[r], k_axis[r]};
  g.slice_positions_mm = std::move(positions);
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  return out;
}

}  // namespace soiq::dicom
