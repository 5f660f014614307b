// The one query table (proto/text/query_options.h) and the command line that reads it, against the
// shared cases (tests/data/shared_cases/query_options.json) the HTTP arguments and the Python client
// are held to as well: the same options, the same requests, the same columns, the same refusals.
#include "proto/text/query_options.h"

#include <gtest/gtest.h>

#include <set>

#include "client/cli/query_args.h"
#include "proto/text/query_columns.h"
#include "tests/support/shared_cases.h"

namespace soiq::proto_text {
namespace {

using soiq::testing::query_args_of;
using soiq::testing::same_message;
using soiq::testing::shared_cases;

Result<v1::QueryRequest> built(const soiq::testing::QueryArgList& args) {
  QueryRequestBuilder b("--");
  for (const auto& [name, value] : args) SOIQ_RETURN_IF_ERROR(b.add(name, value));
  return b.finish();
}

Result<cli::QueryArgs> from_command_line(const soiq::testing::QueryArgList& args) {
  std::vector<std::string> words = {"query"};
  for (const auto& [name, value] : args) {
    words.push_back("--" + name);
    const QueryOption* o = find_query_option(name);
    if (o == nullptr || !o->value.empty())
      words.push_back(value);
    else if (value == "false")
      words.pop_back();  // a flag is given or not
    else if (value != "true")
      words.back() += "=" + value;  // no such spelling: the parser must refuse it
  }
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  return cli::parse_query_args(int(words.size()), argv.data());
}

TEST(QueryTable, HasTheSharedCasesOptionsInOrder) {
  std::vector<std::string> names;
  for (const QueryOption& o : query_options()) names.push_back(std::string(o.name));
  EXPECT_EQ(names, shared_cases("query_options.json").at("options").get<std::vector<std::string>>());
}

TEST(QueryTable, EveryOptionIsInAnAcceptedAndARefusedCase) {
  std::set<std::string> accepted, refused;
  const auto cases = shared_cases("query_options.json");
  for (const auto& c : cases.at("accepted"))
    for (const auto& [name, value] : query_args_of(c)) accepted.insert(name);
  for (const auto& c : cases.at("refused")) refused.insert(c.at("option").get<std::string>());
  for (const QueryOption& o : query_options()) {
    EXPECT_TRUE(accepted.count(std::string(o.name))) << o.name << " has no accepted case";
    // Every option with a value that can be wrong; patient, modality and description take any text
    // but control characters, and patient stands for them.
    if (o.name != "modality" && o.name != "description") {
      EXPECT_TRUE(refused.count(std::string(o.name))) << o.name << " has no refused case";
    }
  }
}

TEST(QueryTable, EveryFieldIsAFieldOfTheRequestAndLeadsBackToItsOption) {
  for (const QueryOption& o : query_options()) {
    const google::protobuf::Descriptor* d = v1::QueryRequest::descriptor();
    std::string path(o.field);
    for (size_t from = 0; d != nullptr;) {
      const size_t dot = std::min(path.find('.', from), path.size());
      const google::protobuf::FieldDescriptor* f = d->FindFieldByName(path.substr(from, dot - from));
      ASSERT_NE(f, nullptr) << o.field;
      if (dot == path.size()) break;
      d = f->message_type();
      from = dot + 1;
    }
    EXPECT_EQ(query_option_of_field(o.field), &o) << o.field;
    if (o.repeatable) {
      EXPECT_EQ(query_option_of_field(std::string(o.field) + "[3].feature"), &o) << o.field;
    }
  }
  EXPECT_EQ(query_option_of_field("grid.spacing_xyz"), find_query_option("spacing"));
  EXPECT_EQ(query_option_of_field("stage1"), nullptr);
}

TEST(QueryTable, AcceptedCasesMakeTheirRequestAndColumnsOnEveryFace) {
  const nlohmann::json cases = shared_cases("query_options.json");
  for (const auto& c : cases.at("accepted")) {
    const auto args = query_args_of(c);
    const Result<v1::QueryRequest> r = built(args);
    ASSERT_TRUE(r.ok()) << c.dump() << ": " << r.status().message();
    EXPECT_TRUE(same_message(c.at("request"), *r)) << c.dump();
    EXPECT_EQ(query_columns(*r).header, c.at("columns").get<std::vector<std::string>>()) << c.dump();
    const Result<cli::QueryArgs> cli = from_command_line(args);
    ASSERT_TRUE(cli.ok()) << c.dump() << ": " << cli.status().message();
    EXPECT_TRUE(same_message(c.at("request"), cli->request)) << c.dump();
  }
}

TEST(QueryTable, RefusedCasesNameTheirOptionOnEveryFace) {
  const nlohmann::json cases = shared_cases("query_options.json");
  for (const auto& c : cases.at("refused")) {
    const auto args = query_args_of(c);
    const std::string option = "--" + c.at("option").get<std::string>();
    const Result<v1::QueryRequest> r = built(args);
    ASSERT_FALSE(r.ok()) << c.dump();
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find(option), std::string::npos) << r.status().message();
    const Result<cli::QueryArgs> cli = from_command_line(args);
    ASSERT_FALSE(cli.ok()) << c.dump();
    EXPECT_NE(cli.status().message().find(option), std::string::npos) << cli.status().message();
  }
}

TEST(QueryTable, ErrorsQuoteTheValueAndGiveTheReason) {
  const Result<v1::QueryRequest> r = built({{"study-date-to", "20230231"}});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(), "--study-date-to '20230231': '20230231' is not a calendar date YYYYMMDD");
  const Result<v1::QueryRequest> w = built({{"where", "sphericity >> 1"}});
  ASSERT_FALSE(w.ok());
  EXPECT_EQ(w.status().message(), "--where 'sphericity >> 1': expected a number at column 13 of 'sphericity >> 1'");
  QueryRequestBuilder url("");
  EXPECT_EQ(url.add("nmae", "x").message(), "unknown option 'nmae'; did you mean 'name'?");
}

TEST(QueryColumns, ARepeatedFeatureIsOneColumnAtItsFirstPlace) {
  const Result<v1::QueryRequest> r =
      built({{"where", "a > 1"}, {"select", "b"}, {"select", "a"}, {"order-by", "b"}, {"select", "c"}});
  ASSERT_TRUE(r.ok());
  const QueryColumns c = query_columns(*r);
  EXPECT_EQ(c.header, (std::vector<std::string>{"id", "patient_id", "study_uid", "name", "laterality", "a", "b", "c"}));
  // Values come as where, select (b, a, c), order_by: a at 0, b at 1, c at 3.
  EXPECT_EQ(c.value_at, (std::vector<size_t>{0, 1, 3}));
}

TEST(Csv, QuotesWhatNeedsItAndWritesNumbersOneWay) {
  EXPECT_EQ(csv_line({"a", "b,c", "say \"hi\"", "line\nbreak", ""}), "a,\"b,c\",\"say \"\"hi\"\"\",\"line\nbreak\",\n");
  EXPECT_EQ(number_text(1.0 / 3.0), "0.3333333333");
  EXPECT_EQ(number_text(std::nan("")), "null");
  EXPECT_EQ(csv_numbers({1, 2.5, -0.125}), "1;2.5;-0.125");
}

}  // namespace
}  // namespace soiq::proto_text
