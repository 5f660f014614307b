#pragma once
// The columns of a query's answer, as every face heads them (`soiq query`'s table, JSON and CSV;
// GET /soiq/v1/query's JSON and CSV; the Python client's keys): the structure's id, patient_id,
// study_uid, name and laterality, then one column per feature of the request in its canonical text
// (feature_text): where's, select's, then order_by's, each name once, at its first place. A row's
// values come in the request's order with repeats (QueryRow.values), so each feature column says
// which value it shows. And the one way numbers and rows are written as text. Pure.

#include <string>
#include <string_view>
#include <vector>

#include "soiq/v1/soiq.pb.h"

namespace soiq::proto_text {

// "id", "patient_id", "study_uid", "name", "laterality".
const std::vector<std::string>& structure_columns();

struct QueryColumns {
  std::vector<std::string> header;  // structure_columns(), then the features
  std::vector<size_t> value_at;     // for header[5 + k], the index of its value in a row's values
};
QueryColumns query_columns(const v1::QueryRequest& request);

// %.10g: ten significant digits, enough for every feature's precision and stable across
// platforms; "null" for NaN and the infinities (as JSON has no such numbers).
std::string number_text(double value);

// One CSV line (RFC 4180): fields joined by ',', a field with a comma, quote or line break quoted
// with its quotes doubled; ends with "\n".
std::string csv_line(const std::vector<std::string>& fields);
// Several numbers of one cell (an array feature) in CSV: number_text joined by ';'.
std::string csv_numbers(const std::vector<double>& values);

}  // namespace soiq::proto_text
