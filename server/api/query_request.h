#pragma once
// A QueryRequest checked and put in the form the query engine runs: stage-1 filter for the store,
// the feature references (predicates', then select's, then order_by's), and one FeatureAsk that
// covers them all (regions x images, so every reference's value is in one computation).
//
// Errors: INVALID_ARGUMENT naming the field — bad sex, laterality or date; min age > max age;
// unknown feature; a bad region; an intensity feature without an image or a shape feature with one;
// a predicate or order on an array feature (centroid_mm, bbox_mm); an unset comparison; limit < 0.

#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "core/regions/regions.h"
#include "db/store.h"
#include "server/app/feature_engine.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

struct ParsedRef {
  std::string name;
  bool intensity = false;  // needs a region and an image
  RegionSpec region;
  std::string image;
  bool asymmetry = false;
  v1::FeatureValue label;  // how rows name it: name, region, image ("asym(name)" for asymmetries)
};

struct ParsedPredicate {
  size_t ref = 0;  // index into ParsedQuery::refs
  v1::ComparisonOp op = v1::LT;
  double value = 0;
};

struct ParsedQuery {
  db::Stage1Filter stage1;
  std::vector<ParsedRef> refs;
  std::vector<ParsedPredicate> where;
  std::optional<size_t> order_ref;
  bool descending = false;
  int limit = 0;
  bool needs_twins = false;
  FeatureAsk ask;  // names empty when the query asks no feature
};

Result<ParsedQuery> parse_query(const v1::QueryRequest& request, int result_cap);

// `value op threshold`; NaN never matches.
bool compare(double value, v1::ComparisonOp op, double threshold);

}  // namespace soiq::server
