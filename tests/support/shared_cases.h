#pragma once
// The cases every face of the query language shares (tests/data/shared_cases/): the query options
// (query_options.json) and the feature grammar (feature_expressions.json), as the C++ tests read
// them; the Python client's tests read the same files. Requests and features are protobuf JSON,
// compared as messages.

#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/test_data.h"

namespace soiq::testing {

using QueryArgList = std::vector<std::pair<std::string, std::string>>;

inline nlohmann::json shared_cases(const std::string& file) {
  return nlohmann::json::parse(file_bytes(test_data("shared_cases/" + file)));
}

inline QueryArgList query_args_of(const nlohmann::json& c) {
  QueryArgList args;
  for (const auto& pair : c.at("args")) args.emplace_back(pair.at(0).get<std::string>(), pair.at(1).get<std::string>());
  return args;
}

// `json` (protobuf JSON) as a message of `got`'s type, compared field by field.
template <typename Message>
::testing::AssertionResult same_message(const nlohmann::json& json, const Message& got) {
  Message want;
  const auto parsed = google::protobuf::util::JsonStringToMessage(json.dump(), &want);
  if (!parsed.ok()) return ::testing::AssertionFailure() << "the case's JSON is not a message: " << json.dump();
  std::string diff;
  google::protobuf::util::MessageDifferencer d;
  d.ReportDifferencesToString(&diff);
  if (d.Compare(want, got)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "want " << want.ShortDebugString() << "\n got " << got.ShortDebugString()
                                       << "\n"
                                       << diff;
}

}  // namespace soiq::testing
