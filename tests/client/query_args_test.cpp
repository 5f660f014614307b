// `soiq query`'s command line beyond the query table (tests/client/query_options_test.cpp holds the
// table's options on every face): --format, words that are not options, and soiqd's errors about a
// field of the request said as the option that set it.
#include "client/cli/query_args.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "client/cli/record_args.h"

namespace soiq::cli {
namespace {

Result<QueryArgs> parse(std::vector<std::string> args) {
  args.insert(args.begin(), "query");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  return parse_query_args(int(args.size()), argv.data());
}

TEST(ParseQueryArgs, AgesAreUnsetWhenNotGiven) {
  const auto a = parse({});
  ASSERT_TRUE(a.ok());
  EXPECT_FALSE(a->request.stage1().has_min_age_years());
  EXPECT_FALSE(a->request.stage1().has_max_age_years());
  EXPECT_FALSE(a->request.has_order_by());
  EXPECT_FALSE(a->request.has_grid());
  EXPECT_EQ(a->format, "table");
}

TEST(ParseQueryArgs, FormatIsTheCommandLinesOwn) {
  const auto a = parse({"--format", "csv", "--desc", "--order-by", "sphericity"});
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  EXPECT_EQ(a->format, "csv");
  EXPECT_TRUE(a->request.descending());
}

struct BadQuery {
  std::vector<std::string> args;
  const char* phrase;
};

class ParseQueryArgsError : public ::testing::TestWithParam<BadQuery> {};

TEST_P(ParseQueryArgsError, IsInvalidArgumentWithAPhrase) {
  const auto a = parse(GetParam().args);
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(a.status().message().find(GetParam().phrase), std::string::npos) << a.status().message();
}

INSTANTIATE_TEST_SUITE_P(Malformed, ParseQueryArgsError,
                         ::testing::Values(BadQuery{{"--where", "mean[shell:5,PT>2"},
                                                    "--where 'mean[shell:5,PT>2': expected ']' at column 16"},
                                           BadQuery{{"--desc"}, "--desc needs --order-by"},
                                           BadQuery{{"--study-date-from", "20230229"},
                                                    "--study-date-from '20230229': '20230229' is not a calendar date"},
                                           BadQuery{{"--series", "1.2.3"}, "unknown option '--series'"},
                                           BadQuery{{"--nmae", "x"}, "did you mean 'name'?"},
                                           BadQuery{{"--format", "xml"}, "--format must be table, json or csv"},
                                           BadQuery{{"volume>3"}, "conditions go in --where"},
                                           BadQuery{{"-x"}, "unknown option '-x'"},
                                           BadQuery{{"--where"}, "--where needs a value"}));

TEST(InCommandLineWords, NamesTheOptionFromTheFieldNotFromTheMessage) {
  const auto a = parse({"--where", "volume_mm3 > 5", "--select", "mean[inside,PT]", "--order-by", "sphericity"});
  ASSERT_TRUE(a.ok()) << a.status().to_string();
  const Status where =
      in_command_line_words(invalid_argument("unknown feature 'volume_mm3'").in_field("where[0]"), a->request);
  EXPECT_EQ(where.message(), "--where 'volume_mm3 > 5': unknown feature 'volume_mm3'");
  EXPECT_EQ(where.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(in_command_line_words(invalid_argument("needs an image").in_field("select[0]"), a->request).message(),
            "--select 'mean[inside,PT]': needs an image");
  EXPECT_EQ(in_command_line_words(invalid_argument("an array").in_field("order_by"), a->request).message(),
            "--order-by 'sphericity': an array");
  EXPECT_EQ(in_command_line_words(invalid_argument("250 is not an age").in_field("stage1.max_age_years"), a->request)
                .message(),
            "--max-age: 250 is not an age");
  // Prose that merely looks like a field is left alone: only Status::field() counts.
  EXPECT_EQ(in_command_line_words(invalid_argument("where[0]: unknown feature"), a->request).message(),
            "where[0]: unknown feature");
  EXPECT_EQ(in_command_line_words(not_found("out of range").in_field("where[7]"), a->request).message(),
            "where[7]: out of range");
  EXPECT_EQ(in_command_line_words(Status(StatusCode::kUnavailable, "no server"), a->request).message(), "no server");
}

TEST(InUploadOptionWords, NamesTheOptionThatSetTheField) {
  EXPECT_EQ(in_upload_option_words(
                invalid_argument("'20230231' is not a calendar date YYYYMMDD").in_field("patient.birth_date"))
                .message(),
            "--birth-date: '20230231' is not a calendar date YYYYMMDD");
  EXPECT_EQ(in_upload_option_words(invalid_argument("is required").in_field("structure_name")).message(),
            "--name: is required");
  EXPECT_EQ(in_upload_option_words(invalid_argument("x").in_field("study.age_years")).message(), "study.age_years: x");
  EXPECT_EQ(in_upload_option_words(not_found("no such study")).message(), "no such study");
}

}  // namespace
}  // namespace soiq::cli
