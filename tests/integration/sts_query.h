#pragma once
// Test support for the STS import tests: their query (GTV structures with the mean PET uptake
// inside), and a query run to its end with every row kept.

#include <vector>

#include "client/soiq_client.h"

namespace soiq::testing {

// Structures named GTV*, selecting mean[inside,PT].
inline v1::QueryRequest gtv_mean_pet_query() {
  v1::QueryRequest q;
  q.mutable_stage1()->set_structure_name_glob("GTV*");
  v1::FeatureRef* mean = q.add_select();
  mean->set_name("mean");
  mean->set_region("inside");
  mean->set_image("PT");
  return q;
}

struct QueryResult {
  std::vector<v1::QueryRow> rows;
  v1::QuerySummary summary;
};

inline Result<QueryResult> run_query(const client::Client& c, const v1::QueryRequest& q) {
  QueryResult out;
  client::QueryHandlers h;
  h.on_row = [&](const v1::QueryRow& row) {
    out.rows.push_back(row);
    return true;
  };
  SOIQ_ASSIGN_OR_RETURN(out.summary, c.query(q, h));
  return out;
}

}  // namespace soiq::testing
