#pragma once
// A two-stage query in the application's own terms (docs/DESIGN.md "Queries"): what the api layer makes
// of a QueryRequest, what the query engine (query_engine.h) runs, and what it hands back. No gRPC
// here: the api turns these into QueryEvent messages.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/base/comparison.h"
#include "core/base/status.h"
#include "core/regions/regions.h"
#include "db/store.h"
#include "server/app/feature_engine.h"

namespace soiq::server {

// How a row names one value: the feature ("asym(name)" for an asymmetry), and for intensity
// features the region ("shell:5") and the image (a modality or a series uid) as the client gave it.
struct FeatureLabel {
  std::string name, region, image;
};

// One feature a query reads: in a predicate, in the selection or as the order.
struct QueryFeature {
  std::string name;        // a catalogue name (core/features/feature_catalogue.h)
  bool intensity = false;  // needs a region and an image
  RegionSpec region;
  std::string image;
  bool asymmetry = false;  // (L - R) / ((L + R) / 2) with the contralateral twin
  FeatureLabel label;
};

struct QueryPredicate {
  size_t feature = 0;  // index into Query::features
  Comparison op = Comparison::kLess;
  double value = 0;
};

struct Query {
  db::Stage1Filter stage1;             // stage1.twins is set when a feature is an asymmetry
  std::vector<QueryFeature> features;  // the predicates', then the selection's, then the order's
  std::vector<QueryPredicate> where;   // joined by AND
  std::optional<size_t> order_by;      // index into features
  bool descending = false;
  int limit = 0;   // >= 1: the api applies the server's cap
  FeatureAsk ask;  // covers every feature; names empty when none is asked
};

// A feature's value in a row; `values` is empty when the structure has none (an asymmetry without
// a twin), one number for scalars, several for arrays (centroid_mm, bbox_mm).
struct RowValue {
  FeatureLabel label;
  std::vector<double> values;
};

struct QueryRow {
  db::StructureRecord structure;
  db::PatientRecord patient;
  db::StudyRecord study;
  std::vector<RowValue> values;  // in the order of Query::features
};

struct QueryProgress {
  std::string stage;  // "stage1", "stage2"
  int64_t done = 0, total = 0;
};

// Structures stage 2 dropped for one reason ("NOT_FOUND: no image series 'PT' in their study ...").
struct QuerySkip {
  std::string reason;
  int64_t count = 0;
  std::vector<int64_t> structure_ids;  // the first few
};

struct QuerySummary {
  int64_t stage1_candidates = 0;
  int64_t computed = 0;    // structures whose features were computed now
  int64_t shared = 0;      // of those, computed through the replicas' shared stage 2 (any replica)
  int64_t cache_hits = 0;  // structures answered from the feature cache
  int64_t matched = 0, returned = 0;
  int64_t failed = 0;                 // structures whose features could not be computed
  std::vector<std::string> failures;  // "structure 12: FAILED_PRECONDITION: ..." (the first 10)
  std::vector<QuerySkip> skipped;     // the `failed` ones grouped by reason, largest group first
  double stage1_ms = 0, stage2_ms = 0, total_ms = 0;
};

// The query's predicates that stage 1 can check on the values precompute stored
// (db::Stage1Filter::stored_features): plain comparisons (not asymmetries) of a stored feature, when
// the query computes its features in the context precompute stored them in (the default spacing,
// a margin of a voxel or more, fill rule non-zero), so the stored value is the one stage 2 would
// compute. Stage 2
// still evaluates every predicate: the rows are the same with or without these, only fewer
// structures reach it.
std::vector<db::StoredFeatureCondition> stored_feature_conditions(const Query& q);

// Where a running query sends what it finds; a non-OK status (the client went away) stops it.
struct QueryOutput {
  std::function<Status(const QueryProgress&)> progress;
  std::function<Status(QueryRow&&)> row;
};

}  // namespace soiq::server
