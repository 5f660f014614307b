#include "bench/mask_agreement.h"

#include "core/base/run_length_volume.h"

namespace soiq::bench {

Result<Agreement> mask_agreement(const Mask& a, const Mask& b) {
  const Result<VolumeComparison> c = compare(from_mask(a), from_mask(b));
  if (!c.ok()) return c.status();
  return Agreement{c->count_a, c->count_b, c->only_a + c->only_b, c->iou()};
}

}  // namespace soiq::bench
