#include "core/voxelize/line_fill.h"

#include <algorithm>
#include <cmath>

#include "core/base/cpu_dispatch.h"

namespace soiq {

namespace {

void append_run(int64_t begin, int64_t end, int64_t nx, int64_t line_first_run, std::vector<Run>& runs) {
  begin = std::max<int64_t>(begin, 0);
  end = std::min<int64_t>(end, nx);
  if (begin >= end) return;
  if (int64_t(runs.size()) > line_first_run && runs.back().end >= begin) {
    runs.back().end = int32_t(std::max<int64_t>(runs.back().end, end));
    return;
  }
  runs.push_back({int32_t(begin), int32_t(end)});
}

void sort_by_centre(LineCrossing* first, LineCrossing* last) {
  // Lines cross a surface a handful of times: insertion sort beats std::sort here.
  if (last - first > 32) {
    std::sort(first, last,
              [](const LineCrossing& a, const LineCrossing& b) { return a.first_centre < b.first_centre; });
    return;
  }
  for (LineCrossing* i = first + 1; i < last; ++i) {
    const LineCrossing v = *i;
    LineCrossing* j = i;
    for (; j > first && (j - 1)->first_centre > v.first_centre; --j) *j = *(j - 1);
    *j = v;
  }
}

}  // namespace

bool fill_line(LineCrossing* first, LineCrossing* last, int64_t nx, FillRule rule, int64_t line_first_run,
               std::vector<Run>& runs) {
  sort_by_centre(first, last);
  int32_t winding = 0;
  bool inside = false;
  int64_t begin = 0;
  // Crossings with the same first centre may come in any order: a momentary flip between them
  // yields an empty or a touching run, which append_run drops or merges, so the result does not
  // depend on the order.
  for (LineCrossing* c = first; c < last; ++c) {
    winding = rule == FillRule::kNonZero ? winding + c->sign : winding ^ 1;
    const bool now = winding != 0;
    if (now == inside) continue;
    inside = now;
    const int64_t edge = c->first_centre;
    if (now) {
      begin = edge;
    } else {
      append_run(begin, edge, nx, line_first_run, runs);
    }
  }
  if (inside) append_run(begin, nx, nx, line_first_run, runs);
  return winding == 0;
}

namespace {

LineRuns fill_lines_here(const std::vector<const std::vector<LineCrossingAt>*>& parts, int64_t first_line,
                         int64_t lines, int64_t nx, FillRule rule, bool drop_unbalanced) {
  // Line l of this range is line first_line + l of the parts; the unsigned comparison also drops
  // lines before the range.
  auto in_range = [&](const LineCrossingAt& c) { return uint64_t(c.line - first_line) < uint64_t(lines); };
  std::vector<int64_t> start(size_t(lines + 1), 0);
  for (const auto* part : parts) {
    for (const LineCrossingAt& c : *part)
      if (in_range(c)) ++start[size_t(c.line - first_line + 1)];
  }
  for (int64_t l = 0; l < lines; ++l) start[size_t(l + 1)] += start[size_t(l)];
  std::vector<LineCrossing> grouped(static_cast<size_t>(start[size_t(lines)]));
  {
    std::vector<int64_t> fill(start.begin(), start.end() - 1);
    for (const auto* part : parts) {
      for (const LineCrossingAt& c : *part)
        if (in_range(c)) grouped[size_t(fill[size_t(c.line - first_line)]++)] = c.crossing;
    }
  }
  LineRuns r;
  r.line_start.resize(size_t(lines + 1));
  for (int64_t l = 0; l < lines; ++l) {
    const int64_t first_run = int64_t(r.runs.size());
    r.line_start[size_t(l)] = first_run;
    LineCrossing* first = grouped.data() + start[size_t(l)];
    LineCrossing* last = grouped.data() + start[size_t(l + 1)];
    if (first == last) continue;
    if (!fill_line(first, last, nx, rule, first_run, r.runs)) {
      ++r.unbalanced_lines;
      if (drop_unbalanced) r.runs.resize(size_t(first_run));
    }
  }
  r.line_start[size_t(lines)] = int64_t(r.runs.size());
  return r;
}

}  // namespace

LineRuns fill_lines(const std::vector<LineCrossingAt>& crossings, int64_t lines, int64_t nx, FillRule rule,
                    bool drop_unbalanced) {
  return cpu_dispatch([&] { return fill_lines_here({&crossings}, 0, lines, nx, rule, drop_unbalanced); });
}

LineRuns fill_lines(const std::vector<const std::vector<LineCrossingAt>*>& parts, int64_t first_line, int64_t lines,
                    int64_t nx, FillRule rule, bool drop_unbalanced) {
  return cpu_dispatch([&] { return fill_lines_here(parts, first_line, lines, nx, rule, drop_unbalanced); });
}

}  // namespace soiq
