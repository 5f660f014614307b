#include "client/cli/row_printer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace soiq::cli {
namespace {

// Everything `print` writes to a temporary FILE.
template <typename Print>
std::string capture(Print print) {
  FILE* f = std::tmpfile();
  print(f);
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text += char(c);
  std::fclose(f);
  return text;
}

TEST(RowPrinter, TableAlignsColumnsUnderTheHeader) {
  const std::string text = capture([](FILE* f) {
    RowPrinter p("table", {"id", "name"}, f);
    p.row({int_cell(7), text_cell("hippocampus")});
    p.row({int_cell(12345), text_cell("amygdala")});
    p.end();
  });
  EXPECT_EQ(text, "id     name\n7      hippocampus\n12345  amygdala\n");
}

TEST(RowPrinter, CsvQuotesOnlyWhereNeeded) {
  const std::string text = capture([](FILE* f) {
    RowPrinter p("csv", {"id", "description"}, f);
    p.row({int_cell(1), text_cell("brain, \"T1\"")});
    p.end();
  });
  EXPECT_EQ(text, "id,description\n1,\"brain, \"\"T1\"\"\"\n");
}

TEST(RowPrinter, JsonIsOneArrayOfObjects) {
  const std::string text = capture([](FILE* f) {
    RowPrinter p("json", {"id", "centroid_mm", "mean"}, f);
    p.row({int_cell(3), numbers_cell({1, 2.5, -3}, false), number_cell(std::nan(""))});
    p.end();
  });
  EXPECT_EQ(text, "[\n  {\"id\": 3, \"centroid_mm\": [1, 2.5, -3], \"mean\": null}\n]\n");
}

TEST(RowPrinter, EmptyJsonIsAnEmptyArray) {
  const std::string text = capture([](FILE* f) {
    RowPrinter p("json", {"id"}, f);
    p.end();
  });
  EXPECT_EQ(text, "[]\n");
}

TEST(NumbersCell, ArraysJoinBySemicolonInCsv) {
  EXPECT_EQ(numbers_cell({1, 2}, true).text, "1;2");
  EXPECT_EQ(numbers_cell({1, 2}, false).text, "(1, 2)");
  EXPECT_EQ(numbers_cell({0.25}, true).text, "0.25");
}

TEST(JsonString, EscapesQuotesBackslashesAndControls) { EXPECT_EQ(json_string("a\"b\\c\n"), "\"a\\\"b\\\\c\\u000a\""); }

}  // namespace
}  // namespace soiq::cli
