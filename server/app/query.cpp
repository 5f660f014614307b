#include "server/app/query.h"

#include <algorithm>
#include <cmath>

namespace soiq::server {

std::vector<db::StoredFeatureCondition> stored_feature_conditions(const Query& q) {
  // Precompute's grid is GridChoice{}; any margin of a voxel or more gives the same values (a shell
  // only widens it: grid_choice.h).
  const GridChoice precompute_grid;
  const GridChoice& grid = q.ask.grid;
  const bool same_values = grid.kind == precompute_grid.kind && grid.spacing_mm == precompute_grid.spacing_mm &&
                           grid.margin_voxels >= 1 && q.ask.fill_rule == FillRule::kNonZero;
  std::vector<db::StoredFeatureCondition> out;
  if (!same_values) return out;
  const std::vector<std::string>& stored = db::stored_feature_names();
  for (const QueryPredicate& p : q.where) {
    const QueryFeature& f = q.features.at(p.feature);
    if (f.intensity || f.asymmetry || std::find(stored.begin(), stored.end(), f.name) == stored.end()) continue;
    out.push_back({f.name, p.op, p.value});
  }
  return out;
}

}  // namespace soiq::server
