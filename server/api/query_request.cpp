#include "server/api/query_request.h"

#include <algorithm>
#include <cmath>

#include "core/features/feature_catalogue.h"
#include "core/regions/regions.h"
#include "server/api/proto_records.h"
#include "server/app/grid_choice.h"

namespace soiq::server {
namespace {

bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

bool is_array_feature(const std::string& name) { return name == "centroid_mm" || name == "bbox_mm"; }

Result<db::Stage1Filter> parse_stage1(const v1::Stage1Filter& s) {
  db::Stage1Filter f;
  SOIQ_RETURN_IF_ERROR(check_sex(s.sex(), "stage1.sex"));
  SOIQ_RETURN_IF_ERROR(check_laterality(s.laterality()));
  const std::pair<const std::string*, const char*> dates[] = {{&s.birth_date_from(), "stage1.birth_date_from"},
                                                              {&s.birth_date_to(), "stage1.birth_date_to"},
                                                              {&s.study_date_from(), "stage1.study_date_from"},
                                                              {&s.study_date_to(), "stage1.study_date_to"}};
  for (const auto& [date, field] : dates) SOIQ_RETURN_IF_ERROR(check_date(*date, field));
  if (s.has_min_age_years() && s.has_max_age_years() && s.min_age_years() > s.max_age_years())
    return invalid_argument("stage1.min_age_years is greater than stage1.max_age_years");
  f.patient_id_glob = s.patient_id_glob();
  f.sex = s.sex();
  if (s.has_min_age_years()) f.min_age_years = s.min_age_years();
  if (s.has_max_age_years()) f.max_age_years = s.max_age_years();
  f.birth_date_from = s.birth_date_from();
  f.birth_date_to = s.birth_date_to();
  f.study_date_from = s.study_date_from();
  f.study_date_to = s.study_date_to();
  f.modality = s.modality();
  f.study_description_glob = s.study_description_glob();
  f.structure_name_glob = s.structure_name_glob();
  f.laterality = s.laterality();
  return f;
}

Result<ParsedRef> parse_ref(const v1::FeatureRef& r, const char* field) {
  ParsedRef p;
  p.name = r.name();
  if (p.name.empty()) return invalid_argument(std::string(field) + ": feature name is empty");
  if (Status known = check_feature_name(p.name); !known.ok())
    return invalid_argument(std::string(field) + ": " + known.message());
  // voxel_count with an image is the region's samples on it, without one the structure's voxels.
  p.intensity = is_intensity_only(p.name) || (find_intensity_feature(p.name) != nullptr && !r.image().empty());
  if (p.intensity) {
    if (r.image().empty())
      return invalid_argument(std::string(field) + ": intensity feature '" + p.name +
                              "' needs an image (a modality of the study such as PT, or a series uid)");
    SOIQ_ASSIGN_OR_RETURN(p.region, parse_region(r.region().empty() ? "inside" : r.region()));
    p.image = r.image();
  } else if (!r.image().empty() || !r.region().empty()) {
    return invalid_argument(std::string(field) + ": shape feature '" + p.name + "' takes no region or image");
  }
  p.asymmetry = r.asymmetry();
  p.label.set_name(p.asymmetry ? "asym(" + p.name + ")" : p.name);
  if (p.intensity) {
    p.label.set_region(region_name(p.region));
    p.label.set_image(p.image);
  }
  return p;
}

}  // namespace

bool compare(double value, v1::ComparisonOp op, double threshold) {
  if (std::isnan(value)) return false;
  switch (op) {
    case v1::LT:
      return value < threshold;
    case v1::LE:
      return value <= threshold;
    case v1::GT:
      return value > threshold;
    case v1::GE:
      return value >= threshold;
    case v1::EQ:
      return value == threshold;
    case v1::NE:
      return value != threshold;
    default:
      return false;
  }
}

Result<ParsedQuery> parse_query(const v1::QueryRequest& request, int result_cap) {
  ParsedQuery q;
  SOIQ_ASSIGN_OR_RETURN(q.stage1, parse_stage1(request.stage1()));
  for (int i = 0; i < request.where_size(); ++i) {
    const v1::Predicate& p = request.where(i);
    const std::string field = "where[" + std::to_string(i) + "]";
    SOIQ_ASSIGN_OR_RETURN(ParsedRef ref, parse_ref(p.feature(), field.c_str()));
    if (is_array_feature(ref.name))
      return invalid_argument(field + ": " + ref.name + " is an array; it can be selected, not compared");
    if (p.op() == v1::COMPARISON_OP_UNSPECIFIED || !v1::ComparisonOp_IsValid(p.op()))
      return invalid_argument(field + ": comparison is not set (LT, LE, GT, GE, EQ or NE)");
    if (!std::isfinite(p.value())) return invalid_argument(field + ": the value must be a finite number");
    q.where.push_back({q.refs.size(), p.op(), p.value()});
    q.refs.push_back(std::move(ref));
  }
  for (int i = 0; i < request.select_size(); ++i) {
    const std::string field = "select[" + std::to_string(i) + "]";
    SOIQ_ASSIGN_OR_RETURN(ParsedRef ref, parse_ref(request.select(i), field.c_str()));
    if (ref.asymmetry && is_array_feature(ref.name))
      return invalid_argument(field + ": the asymmetry of an array feature is not defined");
    q.refs.push_back(std::move(ref));
  }
  if (request.has_order_by()) {
    SOIQ_ASSIGN_OR_RETURN(ParsedRef ref, parse_ref(request.order_by(), "order_by"));
    if (is_array_feature(ref.name)) return invalid_argument("order_by: " + ref.name + " is an array");
    q.order_ref = q.refs.size();
    q.refs.push_back(std::move(ref));
  }
  q.descending = request.descending();
  if (request.limit() < 0) return invalid_argument("limit must be >= 0 (0: the server's cap)");
  q.limit = request.limit() == 0 ? result_cap : std::min(request.limit(), result_cap);

  SOIQ_ASSIGN_OR_RETURN(q.ask.grid, grid_choice(request.grid()));
  SOIQ_RETURN_IF_ERROR(check_enum(request.interpolation(), v1::Interpolation_IsValid, "interpolation"));
  q.ask.interpolation = request.interpolation() == v1::LINEAR ? Interpolation::kLinear : Interpolation::kNearest;
  for (const ParsedRef& r : q.refs) {
    q.needs_twins = q.needs_twins || r.asymmetry;
    if (!contains(q.ask.names, r.name)) q.ask.names.push_back(r.name);
    if (!r.intensity) continue;
    const bool region_known = std::any_of(q.ask.regions.begin(), q.ask.regions.end(),
                                          [&](const RegionSpec& s) { return region_name(s) == region_name(r.region); });
    if (!region_known) q.ask.regions.push_back(r.region);
    if (!contains(q.ask.images, r.image)) q.ask.images.push_back(r.image);
  }
  if (!q.ask.names.empty()) SOIQ_RETURN_IF_ERROR(complete_feature_ask(q.ask));
  return q;
}

}  // namespace soiq::server
