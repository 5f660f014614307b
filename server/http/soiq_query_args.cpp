#include "server/http/soiq_query_args.h"

#include <cmath>
#include <cstdlib>
#include <set>

#include "core/base/did_you_mean.h"
#include "proto/text/feature_expression.h"

namespace soiq::server::http {
namespace {

const std::vector<std::string>& known_args() {
  static const std::vector<std::string> kArgs = {
      "patient",       "sex",      "min-age",     "max-age", "birth-date-from", "birth-date-to",   "study-date-from",
      "study-date-to", "modality", "description", "name",    "laterality",      "where",           "select",
      "order-by",      "desc",     "limit",       "spacing", "margin",          "series-modality", "interpolation"};
  return kArgs;
}

Result<double> number(const std::string& name, const std::string& v) {
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (v.empty() || end != v.c_str() + v.size() || !std::isfinite(d))
    return invalid_argument(name + " must be a number, not '" + v + "'");
  return d;
}

Result<int> integer(const std::string& name, const std::string& v, int lo, int hi) {
  SOIQ_ASSIGN_OR_RETURN(const double d, number(name, v));
  if (d != std::floor(d) || d < lo || d > hi)
    return invalid_argument(name + " must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                            ", not '" + v + "'");
  return int(d);
}

Status in_arg(const Status& s, const std::string& name, const std::string& value) {
  return s.ok() ? s : Status(s.code(), name + "='" + value + "': " + s.message());
}

}  // namespace

Result<v1::QueryRequest> parse_soiq_query_args(const std::vector<std::pair<std::string, std::string>>& args) {
  v1::QueryRequest r;
  v1::Stage1Filter& s = *r.mutable_stage1();
  std::set<std::string> seen;
  bool desc = false, margin = false;
  for (const auto& [name, v] : args) {
    const auto& known = known_args();
    if (std::find(known.begin(), known.end(), name) == known.end())
      return invalid_argument("unknown query argument '" + name + "'" + did_you_mean(name, known) +
                              "; the arguments are soiq query's options without their dashes");
    if (name != "where" && name != "select" && !seen.insert(name).second)
      return invalid_argument("query argument '" + name + "' is given twice");
    if (name == "patient") {
      s.set_patient_id_glob(v);
    } else if (name == "sex") {
      s.set_sex(v);
    } else if (name == "min-age") {
      SOIQ_ASSIGN_OR_RETURN(const double d, number(name, v));
      s.set_min_age_years(d);
    } else if (name == "max-age") {
      SOIQ_ASSIGN_OR_RETURN(const double d, number(name, v));
      s.set_max_age_years(d);
    } else if (name == "birth-date-from") {
      s.set_birth_date_from(v);
    } else if (name == "birth-date-to") {
      s.set_birth_date_to(v);
    } else if (name == "study-date-from") {
      s.set_study_date_from(v);
    } else if (name == "study-date-to") {
      s.set_study_date_to(v);
    } else if (name == "modality") {
      s.set_modality(v);
    } else if (name == "description") {
      s.set_study_description_glob(v);
    } else if (name == "name") {
      s.set_structure_name_glob(v);
    } else if (name == "laterality") {
      s.set_laterality(v);
    } else if (name == "where") {
      Result<v1::Predicate> p = proto_text::parse_predicate(v);
      SOIQ_RETURN_IF_ERROR(in_arg(p.status(), name, v));
      *r.add_where() = *p;
    } else if (name == "select" || name == "order-by") {
      Result<v1::FeatureRef> f = proto_text::parse_feature(v);
      SOIQ_RETURN_IF_ERROR(in_arg(f.status(), name, v));
      *(name == "select" ? r.add_select() : r.mutable_order_by()) = *f;
    } else if (name == "desc") {
      if (v != "true" && v != "false" && !v.empty()) return invalid_argument("desc must be true or false");
      desc = v != "false";
    } else if (name == "limit") {
      SOIQ_ASSIGN_OR_RETURN(const int n, integer(name, v, 1, 1 << 30));
      r.set_limit(n);
    } else if (name == "spacing") {
      std::vector<double> xyz;
      size_t from = 0;
      while (from <= v.size()) {
        const size_t comma = std::min(v.find(',', from), v.size());
        SOIQ_ASSIGN_OR_RETURN(const double d, number(name, v.substr(from, comma - from)));
        if (d <= 0) return invalid_argument("spacing must be > 0 mm, not '" + v + "'");
        xyz.push_back(d);
        from = comma + 1;
      }
      if (xyz.size() == 1) {
        r.mutable_grid()->set_spacing_mm(xyz[0]);
      } else if (xyz.size() == 3) {
        r.mutable_grid()->mutable_spacing_xyz()->set_x(xyz[0]);
        r.mutable_grid()->mutable_spacing_xyz()->set_y(xyz[1]);
        r.mutable_grid()->mutable_spacing_xyz()->set_z(xyz[2]);
      } else {
        return invalid_argument("spacing is S or SX,SY,SZ in mm, not '" + v + "'");
      }
    } else if (name == "margin") {
      SOIQ_ASSIGN_OR_RETURN(const int m, integer(name, v, 0, 1000000));
      r.mutable_grid()->set_margin_voxels(m);
      margin = true;
    } else if (name == "series-modality") {
      r.mutable_grid()->set_series_modality(v);
    } else if (name == "interpolation") {
      if (v != "nearest" && v != "linear") return invalid_argument("interpolation must be nearest or linear");
      r.set_interpolation(v == "linear" ? v1::LINEAR : v1::NEAREST);
    }
  }
  if (desc && !r.has_order_by()) return invalid_argument("desc needs order-by=FEATURE");
  r.set_descending(desc);
  const bool spacing = seen.count("spacing") > 0;
  if (spacing && seen.count("series-modality") > 0)
    return invalid_argument("give either spacing or series-modality, not both");
  if (margin && !spacing) return invalid_argument("margin goes with spacing");
  return r;
}

}  // namespace soiq::server::http
