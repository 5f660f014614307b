#include "server/api/query_request.h"

#include <algorithm>
#include <cmath>

#include "core/features/feature_catalogue.h"
#include "core/regions/regions.h"
#include "proto/text/feature_expression.h"
#include "server/api/grid_spec.h"
#include "server/api/proto_records.h"
#include "server/app/modality_names.h"

namespace soiq::server {
namespace {

bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

// A feature of several values (a point, a box) can be selected, but not compared or ordered by.
bool is_array_feature(const std::string& name) {
  const FeatureDef* f = find_shape_feature(name);
  if (f == nullptr) f = find_intensity_feature(name);
  if (f == nullptr) f = mask_feature(name);
  return f != nullptr && f->components > 1;
}

Result<db::Stage1Filter> parse_stage1(const v1::Stage1Filter& s) {
  db::Stage1Filter f;
  // Each field by its one rule (core/base/field_rules.h), the error in the field's path.
  SOIQ_RETURN_IF_ERROR(check_sex(s.sex()).in_field("stage1.sex"));
  SOIQ_RETURN_IF_ERROR(check_laterality(s.laterality()).in_field("stage1.laterality"));
  const std::pair<const std::string*, const char*> dates[] = {{&s.birth_date_from(), "stage1.birth_date_from"},
                                                              {&s.birth_date_to(), "stage1.birth_date_to"},
                                                              {&s.study_date_from(), "stage1.study_date_from"},
                                                              {&s.study_date_to(), "stage1.study_date_to"}};
  for (const auto& [date, field] : dates) SOIQ_RETURN_IF_ERROR(check_date(*date).in_field(field));
  const std::pair<const std::string*, const char*> texts[] = {
      {&s.patient_id_glob(), "stage1.patient_id_glob"},
      {&s.study_description_glob(), "stage1.study_description_glob"},
      {&s.structure_name_glob(), "stage1.structure_name_glob"}};
  for (const auto& [text, field] : texts) SOIQ_RETURN_IF_ERROR(check_text(*text, kMaxNameBytes).in_field(field));
  SOIQ_RETURN_IF_ERROR(check_text(s.modality(), kMaxIdBytes).in_field("stage1.modality"));
  if (s.has_min_age_years()) SOIQ_RETURN_IF_ERROR(check_age_years(s.min_age_years()).in_field("stage1.min_age_years"));
  if (s.has_max_age_years()) SOIQ_RETURN_IF_ERROR(check_age_years(s.max_age_years()).in_field("stage1.max_age_years"));
  if (s.has_min_age_years() && s.has_max_age_years() && s.min_age_years() > s.max_age_years())
    return invalid_argument("is greater than stage1.max_age_years").in_field("stage1.min_age_years");
  f.patient_id_glob = s.patient_id_glob();
  f.sex = s.sex();
  if (s.has_min_age_years()) f.min_age_years = s.min_age_years();
  if (s.has_max_age_years()) f.max_age_years = s.max_age_years();
  f.birth_date_from = s.birth_date_from();
  f.birth_date_to = s.birth_date_to();
  f.study_date_from = s.study_date_from();
  f.study_date_to = s.study_date_to();
  f.modality = dicom_modality(s.modality());
  f.study_description_glob = s.study_description_glob();
  f.structure_name_glob = s.structure_name_glob();
  f.laterality = s.laterality();
  return f;
}

Result<QueryFeature> parse_ref(const v1::FeatureRef& r, const char* field) {
  QueryFeature p;
  p.name = r.name();
  if (p.name.empty()) return invalid_argument("feature name is empty").in_field(field);
  if (Status known = check_feature_name(p.name); !known.ok()) return invalid_argument(known.message()).in_field(field);
  // voxel_count with an image is the region's samples on it, without one the structure's voxels.
  p.intensity = is_intensity_only(p.name) || (find_intensity_feature(p.name) != nullptr && !r.image().empty());
  if (p.intensity) {
    if (r.image().empty())
      return invalid_argument("intensity feature '" + p.name +
                              "' needs an image (a modality of the study such as PT, or a series uid)")
          .in_field(field);
    Result<RegionSpec> region = parse_region(r.region().empty() ? "inside" : r.region());
    if (!region.ok()) return region.status().in_field(field);
    p.region = *region;
    // Coverage weights and the centre of mass shift exist for the structure itself only.
    if (const FeatureDef* def = find_intensity_feature(p.name);
        def && def->needs.has(FeatureNeed::kInsideRegion) && region->kind != RegionKind::kInside) {
      return invalid_argument("'" + p.name + "' is given for the inside region only, not " + region_name(*region))
          .in_field(field);
    }
    p.image = dicom_modality(r.image());
  } else if (!r.image().empty() || !r.region().empty()) {
    return invalid_argument("shape feature '" + p.name + "' takes no region or image").in_field(field);
  }
  p.asymmetry = r.asymmetry();
  p.label.name = p.asymmetry ? "asym(" + p.name + ")" : p.name;
  if (p.intensity) {
    p.label.region = region_name(p.region);
    p.label.image = p.image;
  }
  return p;
}

Result<Comparison> comparison_of(v1::ComparisonOp op, const std::string& field) {
  const std::optional<Comparison> c = proto_text::comparison_of(op);
  if (!c) return invalid_argument("comparison is not set (LT, LE, GT, GE, EQ or NE)").in_field(field);
  return *c;
}

}  // namespace

Result<Query> parse_query(const v1::QueryRequest& request, int result_cap) {
  Query q;
  SOIQ_ASSIGN_OR_RETURN(q.stage1, parse_stage1(request.stage1()));
  for (int i = 0; i < request.where_size(); ++i) {
    const v1::Predicate& p = request.where(i);
    const std::string field = "where[" + std::to_string(i) + "]";
    SOIQ_ASSIGN_OR_RETURN(QueryFeature ref, parse_ref(p.feature(), field.c_str()));
    if (is_array_feature(ref.name))
      return invalid_argument(ref.name + " is an array; it can be selected, not compared").in_field(field);
    SOIQ_ASSIGN_OR_RETURN(const Comparison op, comparison_of(p.op(), field));
    if (!std::isfinite(p.value())) return invalid_argument("the value must be a finite number").in_field(field);
    q.where.push_back({q.features.size(), op, p.value()});
    q.features.push_back(std::move(ref));
  }
  for (int i = 0; i < request.select_size(); ++i) {
    const std::string field = "select[" + std::to_string(i) + "]";
    SOIQ_ASSIGN_OR_RETURN(QueryFeature ref, parse_ref(request.select(i), field.c_str()));
    if (ref.asymmetry && is_array_feature(ref.name))
      return invalid_argument("the asymmetry of an array feature is not defined").in_field(field);
    q.features.push_back(std::move(ref));
  }
  if (request.has_order_by()) {
    SOIQ_ASSIGN_OR_RETURN(QueryFeature ref, parse_ref(request.order_by(), "order_by"));
    if (is_array_feature(ref.name)) return invalid_argument(ref.name + " is an array").in_field("order_by");
    q.order_by = q.features.size();
    q.features.push_back(std::move(ref));
  }
  q.descending = request.descending();
  if (request.limit() < 0) return invalid_argument("must be >= 0 (0: the server's cap)").in_field("limit");
  q.limit = request.limit() == 0 ? result_cap : std::min(request.limit(), result_cap);

  SOIQ_ASSIGN_OR_RETURN(q.ask.grid, grid_choice(request.grid()));
  SOIQ_RETURN_IF_ERROR(check_enum(request.interpolation(), v1::Interpolation_IsValid, "interpolation"));
  q.ask.interpolation = request.interpolation() == v1::LINEAR ? Interpolation::kLinear : Interpolation::kNearest;
  for (const QueryFeature& r : q.features) {
    q.stage1.twins = q.stage1.twins || r.asymmetry;
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

v1::QueryEvent to_event(const QueryProgress& p) {
  v1::QueryEvent e;
  e.mutable_progress()->set_stage(p.stage);
  e.mutable_progress()->set_done(p.done);
  e.mutable_progress()->set_total(p.total);
  return e;
}

v1::QueryEvent to_event(const QueryRow& r) {
  v1::QueryEvent e;
  v1::QueryRow* row = e.mutable_row();
  *row->mutable_structure() = to_proto(r.structure);
  *row->mutable_patient() = to_proto(r.patient);
  *row->mutable_study() = to_proto(r.study);
  for (const RowValue& v : r.values) {
    v1::FeatureValue* out = row->add_values();
    out->set_name(v.label.name);
    out->set_region(v.label.region);
    out->set_image(v.label.image);
    for (double x : v.values) out->add_value(x);
  }
  return e;
}

v1::QueryEvent to_event(const QuerySummary& s) {
  v1::QueryEvent e;
  v1::QuerySummary* out = e.mutable_summary();
  out->set_stage1_candidates(s.stage1_candidates);
  out->set_computed(s.computed);
  out->set_cache_hits(s.cache_hits);
  out->set_matched(s.matched);
  out->set_returned(s.returned);
  out->set_failed(s.failed);
  for (const std::string& f : s.failures) out->add_failures(f);
  for (const QuerySkip& k : s.skipped) {
    v1::QuerySkip* skip = out->add_skipped();
    skip->set_reason(k.reason);
    skip->set_count(k.count);
    for (int64_t id : k.structure_ids) skip->add_structure_ids(id);
  }
  out->set_stage1_ms(s.stage1_ms);
  out->set_stage2_ms(s.stage2_ms);
  out->set_total_ms(s.total_ms);
  return e;
}

}  // namespace soiq::server
