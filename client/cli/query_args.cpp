#include "client/cli/query_args.h"

#include <charconv>
#include <cstdio>

#include "client/cli/record_args.h"
#include "client/cli/row_printer.h"
#include "proto/text/feature_expression.h"
#include "proto/text/query_options.h"
#include "render/picture.h"

namespace soiq::cli {

Result<QueryArgs> parse_query_args(int argc, char** argv) {
  QueryArgs a;
  proto_text::QueryRequestBuilder request("--");
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--format") {
      SOIQ_ASSIGN_OR_RETURN(a.format, option_value(argc, argv, i));
      SOIQ_RETURN_IF_ERROR(check_row_format(a.format));
      continue;
    }
    if (arg == "--plot") {
      SOIQ_ASSIGN_OR_RETURN(a.plot, option_value(argc, argv, i));
      const Result<render::PictureFormat> format = render::picture_format_of_path(a.plot);
      if (!format.ok() || *format == render::PictureFormat::kJpeg)
        return invalid_argument("--plot '" + a.plot + "': a plot is written as .png or .svg");
      continue;
    }
    if (!arg.starts_with("--")) {
      if (arg.size() > 1 && arg[0] == '-') return invalid_argument("unknown option '" + arg + "'");
      return invalid_argument("unexpected argument '" + arg + "' (conditions go in --where 'EXPR')");
    }
    const std::string name = arg.substr(2);
    const proto_text::QueryOption* option = proto_text::find_query_option(name);
    std::string value = "true";  // a flag's
    if (option != nullptr && !option->value.empty()) {
      SOIQ_ASSIGN_OR_RETURN(value, option_value(argc, argv, i));
    }
    SOIQ_RETURN_IF_ERROR(request.add(name, value));
  }
  SOIQ_ASSIGN_OR_RETURN(a.request, request.finish());
  if (!a.plot.empty() && a.request.select_size() == 0 && a.request.where_size() == 0 && !a.request.has_order_by())
    return invalid_argument("--plot needs a feature to draw: add --select FEATURE (two for a scatter)");
  return a;
}

Status in_command_line_words(const Status& status, const soiq::v1::QueryRequest& r) {
  const std::string& field = status.field();
  const proto_text::QueryOption* option = proto_text::query_option_of_field(field);
  if (option == nullptr) return status;
  const std::string flag = "--" + std::string(option->name);
  // where[i] and select[i] name one of several uses: shown with its expression.
  int index = -1;
  if (const size_t open = field.find('['); open != std::string::npos) {
    const char* first = field.data() + open + 1;
    const char* last = field.data() + field.size();
    if (std::from_chars(first, last, index).ec != std::errc()) index = -1;
  }
  std::string text;
  if (option->name == "where" && index >= 0 && index < r.where_size()) {
    const soiq::v1::Predicate& p = r.where(index);
    char value[32];
    std::snprintf(value, sizeof value, "%g", p.value());
    text = proto_text::feature_text(p.feature()) + " " + proto_text::comparison_text(p.op()) + " " + value;
  } else if (option->name == "select" && index >= 0 && index < r.select_size()) {
    text = proto_text::feature_text(r.select(index));
  } else if (option->name == "order-by" && r.has_order_by()) {
    text = proto_text::feature_text(r.order_by());
  } else if (option->repeatable) {
    return status;  // an index the request does not have: the server's words are all there is
  }
  return Status(status.code(), flag + (text.empty() ? "" : " '" + text + "'") + ": " + status.reason());
}

}  // namespace soiq::cli
