#include "client/cli/query_args.h"

#include <charconv>
#include <cstdio>

#include "client/cli/cli_args.h"
#include "client/cli/grid_args.h"
#include "client/cli/record_args.h"
#include "client/cli/row_printer.h"
#include "proto/text/feature_expression.h"

namespace soiq::cli {

namespace {

// Stage-1 options that take a value; false when argv[i] is not one.
Result<bool> parse_stage1_option(int argc, char** argv, int& i, soiq::v1::Stage1Filter& s) {
  const std::string arg = argv[i];
  static const char* const kOptions[] = {"--patient",
                                         "--sex",
                                         "--min-age",
                                         "--max-age",
                                         "--birth-date-from",
                                         "--birth-date-to",
                                         "--study-date-from",
                                         "--study-date-to",
                                         "--modality",
                                         "--description",
                                         "--name",
                                         "--laterality"};
  bool known = false;
  for (const char* o : kOptions) known = known || arg == o;
  if (!known) return false;
  SOIQ_ASSIGN_OR_RETURN(const std::string v, option_value(argc, argv, i));
  if (arg == "--patient") s.set_patient_id_glob(v);
  if (arg == "--sex") {
    SOIQ_RETURN_IF_ERROR(check_sex(v));
    s.set_sex(v);
  }
  if (arg == "--min-age" || arg == "--max-age") {
    SOIQ_ASSIGN_OR_RETURN(const double years, parse_number(v, arg));
    if (years < 0) return invalid_argument(arg + " must be >= 0 years");
    arg == "--min-age" ? s.set_min_age_years(years) : s.set_max_age_years(years);
  }
  if (arg.find("date") != std::string::npos) SOIQ_RETURN_IF_ERROR(check_date(v, arg));  // the four date bounds
  if (arg == "--birth-date-from") s.set_birth_date_from(v);
  if (arg == "--birth-date-to") s.set_birth_date_to(v);
  if (arg == "--study-date-from") s.set_study_date_from(v);
  if (arg == "--study-date-to") s.set_study_date_to(v);
  if (arg == "--modality") s.set_modality(v);
  if (arg == "--description") s.set_study_description_glob(v);
  if (arg == "--name") s.set_structure_name_glob(v);
  if (arg == "--laterality") {
    SOIQ_RETURN_IF_ERROR(check_laterality(v));
    s.set_laterality(v);
  }
  return true;
}

// "--where 'mean[shell:0]>2': region 'shell:0' needs ..." names the flag the expression came from.
Status in_flag(const Status& s, const std::string& flag) {
  return s.ok() ? s : Status(s.code(), flag + ": " + s.message());
}

}  // namespace

Result<QueryArgs> parse_query_args(int argc, char** argv) {
  QueryArgs a;
  soiq::v1::QueryRequest& r = a.request;
  GridArgs grid;
  grid.allow_series_uid = false;
  bool desc = false;
  for (int i = 1; i < argc; ++i) {
    SOIQ_ASSIGN_OR_RETURN(const bool stage1, parse_stage1_option(argc, argv, i, *r.mutable_stage1()));
    if (stage1) continue;
    SOIQ_ASSIGN_OR_RETURN(const bool is_grid, parse_grid_option(argc, argv, i, grid));
    if (is_grid) continue;
    const std::string arg = argv[i];
    if (arg == "--desc") {
      desc = true;
      continue;
    }
    if (arg != "--where" && arg != "--select" && arg != "--order-by" && arg != "--limit" && arg != "--format" &&
        arg != "--interpolation") {
      if (arg.size() > 1 && arg[0] == '-') return invalid_argument("unknown option '" + arg + "'");
      return invalid_argument("unexpected argument '" + arg + "' (conditions go in --where 'EXPR')");
    }
    SOIQ_ASSIGN_OR_RETURN(const std::string v, option_value(argc, argv, i));
    if (arg == "--where") {
      Result<soiq::v1::Predicate> p = proto_text::parse_predicate(v);
      SOIQ_RETURN_IF_ERROR(in_flag(p.status(), arg));
      *r.add_where() = *p;
    } else if (arg == "--select" || arg == "--order-by") {
      Result<soiq::v1::FeatureRef> f = proto_text::parse_feature(v);
      SOIQ_RETURN_IF_ERROR(in_flag(f.status(), arg));
      if (arg == "--select") {
        *r.add_select() = *f;
      } else {
        if (r.has_order_by()) return invalid_argument("--order-by is given twice");
        *r.mutable_order_by() = *f;
      }
    } else if (arg == "--limit") {
      SOIQ_ASSIGN_OR_RETURN(const int limit, parse_int(v, "--limit", 1, 1 << 30));
      r.set_limit(limit);
    } else if (arg == "--format") {
      SOIQ_RETURN_IF_ERROR(check_row_format(v));
      a.format = v;
    } else {
      if (v != "nearest" && v != "linear") return invalid_argument("--interpolation must be nearest or linear");
      r.set_interpolation(v == "linear" ? soiq::v1::LINEAR : soiq::v1::NEAREST);
    }
  }
  if (desc && !r.has_order_by()) return invalid_argument("--desc needs --order-by FEATURE");
  r.set_descending(desc);
  SOIQ_RETURN_IF_ERROR(check_grid_args(grid));
  if (grid.given || grid.margin_given) *r.mutable_grid() = grid.grid;
  return a;
}

std::vector<std::string> query_feature_columns(const soiq::v1::QueryRequest& r) {
  std::vector<std::string> columns;
  for (const auto& p : r.where()) columns.push_back(proto_text::feature_text(p.feature()));
  for (const auto& f : r.select()) columns.push_back(proto_text::feature_text(f));
  if (r.has_order_by()) columns.push_back(proto_text::feature_text(r.order_by()));
  return columns;
}

Status in_command_line_words(const Status& status, const soiq::v1::QueryRequest& r) {
  const std::string& m = status.message();
  std::string flag, field;
  int index = 0;
  for (const char* name : {"where", "select"}) {
    const std::string prefix = std::string(name) + "[";
    if (!m.starts_with(prefix)) continue;
    const size_t close = m.find("]: ");
    if (close == std::string::npos) return status;
    const char* first = m.data() + prefix.size();
    const auto [end, ec] = std::from_chars(first, m.data() + close, index);
    if (ec != std::errc() || end != m.data() + close) return status;
    flag = std::string("--") + name;
    field = m.substr(0, close + 3);
  }
  if (m.starts_with("order_by: ") && r.has_order_by()) {
    return Status(status.code(),
                  "--order-by '" + proto_text::feature_text(r.order_by()) + "': " + m.substr(sizeof("order_by: ") - 1));
  }
  std::string text;
  if (flag == "--where" && index >= 0 && index < r.where_size()) {
    const soiq::v1::Predicate& p = r.where(index);
    char value[32];
    std::snprintf(value, sizeof value, "%g", p.value());
    text = proto_text::feature_text(p.feature()) + " " + proto_text::comparison_text(p.op()) + " " + value;
  } else if (flag == "--select" && index >= 0 && index < r.select_size()) {
    text = proto_text::feature_text(r.select(index));
  } else {
    return status;
  }
  return Status(status.code(), flag + " '" + text + "': " + m.substr(field.size()));
}

std::vector<size_t> distinct_columns(const std::vector<std::string>& columns) {
  std::vector<size_t> keep;
  for (size_t c = 0; c < columns.size(); ++c) {
    bool seen = false;
    for (const size_t k : keep) seen = seen || columns[k] == columns[c];
    if (!seen) keep.push_back(c);
  }
  return keep;
}

}  // namespace soiq::cli
