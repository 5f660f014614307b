#include "proto/text/query_options.h"

#include <cmath>
#include <cstdlib>
#include <vector>

#include "core/base/did_you_mean.h"
#include "core/base/field_rules.h"
#include "proto/text/feature_expression.h"

namespace soiq::proto_text {
namespace {

using v1::QueryRequest;

Result<double> number(const std::string& v) {
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (v.empty() || end != v.c_str() + v.size() || !std::isfinite(d))
    return invalid_argument("'" + v.substr(0, 40) + "' is not a number");
  return d;
}

Result<int> integer(const std::string& v, int lo, int hi) {
  Result<double> d = number(v);
  if (!d.ok() || *d != std::floor(*d) || *d < lo || *d > hi)
    return invalid_argument("'" + v.substr(0, 40) + "' is not a whole number in " + std::to_string(lo) + ".." +
                            std::to_string(hi));
  return int(*d);
}

Result<double> years(const std::string& v) {
  SOIQ_ASSIGN_OR_RETURN(const double y, number(v));
  SOIQ_RETURN_IF_ERROR(check_age_years(y));
  return y;
}

// Sets a string field after the field's rule.
template <void (v1::Stage1Filter::*Set)(const std::string&)>
Status glob(const std::string& v, QueryRequest& r) {
  SOIQ_RETURN_IF_ERROR(check_text(v, kMaxNameBytes));
  (r.mutable_stage1()->*Set)(v);
  return ok_status();
}

template <void (v1::Stage1Filter::*Set)(const std::string&)>
Status date(const std::string& v, QueryRequest& r) {
  SOIQ_RETURN_IF_ERROR(check_date(v));
  (r.mutable_stage1()->*Set)(v);
  return ok_status();
}

Status sex(const std::string& v, QueryRequest& r) {
  SOIQ_RETURN_IF_ERROR(check_sex(v));
  r.mutable_stage1()->set_sex(v);
  return ok_status();
}

Status min_age(const std::string& v, QueryRequest& r) {
  SOIQ_ASSIGN_OR_RETURN(const double y, years(v));
  r.mutable_stage1()->set_min_age_years(y);
  return ok_status();
}

Status max_age(const std::string& v, QueryRequest& r) {
  SOIQ_ASSIGN_OR_RETURN(const double y, years(v));
  r.mutable_stage1()->set_max_age_years(y);
  return ok_status();
}

Status modality(const std::string& v, QueryRequest& r) {
  SOIQ_RETURN_IF_ERROR(check_text(v, kMaxIdBytes));
  r.mutable_stage1()->set_modality(v);
  return ok_status();
}

Status laterality(const std::string& v, QueryRequest& r) {
  SOIQ_RETURN_IF_ERROR(check_laterality(v));
  r.mutable_stage1()->set_laterality(v);
  return ok_status();
}

Status where(const std::string& v, QueryRequest& r) {
  SOIQ_ASSIGN_OR_RETURN(*r.add_where(), parse_predicate(v));
  return ok_status();
}

Status select(const std::string& v, QueryRequest& r) {
  SOIQ_ASSIGN_OR_RETURN(*r.add_select(), parse_feature(v));
  return ok_status();
}

Status order_by(const std::string& v, QueryRequest& r) {
  SOIQ_ASSIGN_OR_RETURN(*r.mutable_order_by(), parse_feature(v));
  return ok_status();
}

// A flag: given alone on the command line ("true"), desc=true|false or a bare "desc" in a URL.
Status desc(const std::string& v, QueryRequest& r) {
  if (v != "true" && v != "false" && !v.empty())
    return invalid_argument("'" + v.substr(0, 40) + "' is not true or false");
  r.set_descending(v != "false");
  return ok_status();
}

Status limit(const std::string& v, QueryRequest& r) {
  SOIQ_ASSIGN_OR_RETURN(const int n, integer(v, 1, 1 << 30));
  r.set_limit(n);
  return ok_status();
}

Status spacing(const std::string& v, QueryRequest& r) { return set_grid_spacing(v, *r.mutable_grid()); }

Status margin(const std::string& v, QueryRequest& r) {
  SOIQ_ASSIGN_OR_RETURN(const int n, integer(v, 0, 1000));
  r.mutable_grid()->set_margin_voxels(n);
  return ok_status();
}

Status series_modality(const std::string& v, QueryRequest& r) {
  if (v.empty()) return invalid_argument("a modality is required (PT, CT, MR, ...)");
  SOIQ_RETURN_IF_ERROR(check_text(v, kMaxIdBytes));
  r.mutable_grid()->set_series_modality(v);
  return ok_status();
}

Status interpolation(const std::string& v, QueryRequest& r) {
  if (v != "nearest" && v != "linear") return invalid_argument("'" + v.substr(0, 40) + "' is not nearest or linear");
  r.set_interpolation(v == "linear" ? v1::LINEAR : v1::NEAREST);
  return ok_status();
}

using S = v1::Stage1Filter;
const QueryOption kOptions[] = {
    {"patient", "GLOB", "", "patient ids (glob: * and ?)", "stage1.patient_id_glob", false, true,
     glob<&S::set_patient_id_glob>},
    {"sex", "M|F|O", "", "the patient's sex", "stage1.sex", false, true, sex},
    {"min-age", "Y", "", "age at the study, in years, at least", "stage1.min_age_years", false, true, min_age},
    {"max-age", "Y", "", "age at the study, in years, at most", "stage1.max_age_years", false, true, max_age},
    {"birth-date-from", "D", "", "born on or after (YYYYMMDD)", "stage1.birth_date_from", false, true,
     date<&S::set_birth_date_from>},
    {"birth-date-to", "D", "", "born on or before (YYYYMMDD)", "stage1.birth_date_to", false, true,
     date<&S::set_birth_date_to>},
    {"study-date-from", "D", "", "studied on or after (YYYYMMDD)", "stage1.study_date_from", false, true,
     date<&S::set_study_date_from>},
    {"study-date-to", "D", "", "studied on or before (YYYYMMDD)", "stage1.study_date_to", false, true,
     date<&S::set_study_date_to>},
    {"modality", "M", "", "a modality of the study (PET means PT)", "stage1.modality", false, true, modality},
    {"description", "GLOB", "", "the study's description", "stage1.study_description_glob", false, true,
     glob<&S::set_study_description_glob>},
    {"name", "GLOB", "", "the structure's name (case-insensitive)", "stage1.structure_name_glob", false, true,
     glob<&S::set_structure_name_glob>},
    {"laterality", "L|R", "", "the structure's side", "stage1.laterality", false, true, laterality},
    {"where", "'FEATURE OP NUMBER'", "", "a condition on a feature; repeatable (all must hold)", "where", true, false,
     where},
    {"select", "FEATURE", "", "a feature column; repeatable", "select", true, false, select},
    {"order-by", "FEATURE", "structure id", "sort the rows by this feature", "order_by", false, false, order_by},
    {"desc", "", "", "sort descending (with order-by; ascending without)", "descending", false, false, desc},
    {"limit", "N", "the server's cap", "at most N rows", "limit", false, false, limit},
    {"spacing", "S|SX,SY,SZ", "1", "grid of the features, in mm (not with series-modality)", "grid.spacing_mm", false,
     false, spacing},
    {"margin", "N", "2", "voxels of margin around the structure (with spacing)", "grid.margin_voxels", false, false,
     margin},
    {"series-modality", "M", "", "compute on the grid of the study's series of modality M", "grid.series_modality",
     false, false, series_modality},
    {"interpolation", "nearest|linear", "nearest", "how images are sampled", "interpolation", false, false,
     interpolation},
};

}  // namespace

std::span<const QueryOption> query_options() { return kOptions; }

const QueryOption* find_query_option(std::string_view name) {
  for (const QueryOption& o : kOptions) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

const QueryOption* query_option_of_field(std::string_view field) {
  for (const QueryOption& o : kOptions) {
    if (field == o.field) return &o;
    // "where[2]", "where[2].feature", "grid.spacing_xyz" under "grid.spacing_mm"'s option.
    if (field.starts_with(o.field) && field.size() > o.field.size() &&
        (field[o.field.size()] == '[' || field[o.field.size()] == '.'))
      return &o;
  }
  if (field.starts_with("grid.spacing_xyz")) return find_query_option("spacing");
  return nullptr;
}

Status set_grid_spacing(const std::string& text, v1::GridSpec& grid) {
  std::vector<double> xyz;
  for (size_t from = 0; from <= text.size();) {
    const size_t comma = std::min(text.find(',', from), text.size());
    const Result<double> d = number(text.substr(from, comma - from));
    if (!d.ok() || *d <= 0)
      return invalid_argument("'" + text.substr(0, 40) + "' is not a spacing: S or SX,SY,SZ in mm, each > 0");
    xyz.push_back(*d);
    from = comma + 1;
  }
  if (xyz.size() != 1 && xyz.size() != 3)
    return invalid_argument("'" + text.substr(0, 40) + "' is not a spacing: S or SX,SY,SZ in mm, each > 0");
  if (xyz.size() == 1 || (xyz[0] == xyz[1] && xyz[1] == xyz[2])) {
    grid.set_spacing_mm(xyz[0]);
  } else {
    grid.mutable_spacing_xyz()->set_x(xyz[0]);
    grid.mutable_spacing_xyz()->set_y(xyz[1]);
    grid.mutable_spacing_xyz()->set_z(xyz[2]);
  }
  return ok_status();
}

Status QueryRequestBuilder::add(const std::string& name, const std::string& value) {
  const QueryOption* o = find_query_option(name);
  if (o == nullptr) {
    std::vector<std::string> names;
    for (const QueryOption& k : kOptions) names.push_back(std::string(k.name));
    return invalid_argument("unknown option '" + spelled(name) + "'" + did_you_mean(name, names));
  }
  if (!o->repeatable && !given_.insert(name).second) return invalid_argument(spelled(name) + " is given twice");
  const Status s = o->apply(value, request_);
  if (s.ok()) return s;
  // The reason in the face's words: "--where 'volume >': expected a number at column 9 of 'volume >'".
  return Status(s.code(),
                spelled(name) + (o->value.empty() ? "" : " '" + value.substr(0, 80) + "'") + ": " + s.message());
}

Result<v1::QueryRequest> QueryRequestBuilder::finish() const {
  const auto given = [&](std::string_view n) { return given_.count(n) > 0; };
  if (request_.descending() && !request_.has_order_by())
    return invalid_argument(spelled("desc") + " needs " + spelled("order-by") + " FEATURE");
  if (given("spacing") && given("series-modality"))
    return invalid_argument("give either " + spelled("spacing") + " or " + spelled("series-modality") + ", not both");
  if (given("margin") && !given("spacing"))
    return invalid_argument(spelled("margin") + " goes with " + spelled("spacing"));
  const v1::Stage1Filter& s = request_.stage1();
  if (s.has_min_age_years() && s.has_max_age_years() && s.min_age_years() > s.max_age_years())
    return invalid_argument(spelled("min-age") + " is above " + spelled("max-age"));
  return request_;
}

}  // namespace soiq::proto_text
