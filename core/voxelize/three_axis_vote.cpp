#include "core/voxelize/three_axis_vote.h"

namespace soiq {

RunLengthVolume three_axis_vote(const ImageGeometry& g, const std::array<AxisRuns, 3>& fills) {
  const int64_t n[3] = {g.dims[0], g.dims[1], g.dims[2]};
  const int64_t stride[3] = {1, n[0], n[0] * n[1]};
  std::vector<uint8_t> votes(size_t(g.voxel_count()), 0);
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const AxisRuns& f = fills[size_t(a)];
    for (int64_t l = 0; l + 1 < int64_t(f.line_start.size()); ++l) {
      const int64_t base = (l % n[b]) * stride[b] + (l / n[b]) * stride[c];
      for (int64_t r = f.line_start[size_t(l)]; r < f.line_start[size_t(l + 1)]; ++r) {
        for (int64_t i = f.runs[size_t(r)].begin; i < f.runs[size_t(r)].end; ++i) ++votes[size_t(base + i * stride[a])];
      }
    }
  }
  Mask m;
  m.geometry = g;
  m.voxels.resize(votes.size());
  for (size_t v = 0; v < votes.size(); ++v) m.voxels[v] = votes[v] >= 2;
  return from_mask(m);
}

}  // namespace soiq
