#pragma once
// Strict tokens for soiq's own text mesh parsers (STL, OBJ, PLY, OFF): lines with their numbers,
// the words of a line, and numbers that must be whole and finite. A hostile upload's bad token
// becomes an INVALID_ARGUMENT naming the file, the line and the token, never a silent 0 or 5.
//
// Inputs   views into the caller's bytes (they must outlive the views returned); `where` is the
//          message prefix, e.g. "OBJ 'a.obj' line 7".
// Output   see each function.
// Errors   INVALID_ARGUMENT "<where>: '5abc' is not a number" / "'nan' is not a finite number" /
//          "'1e999' is out of range" / "'1.5' is not an integer".
// Cost     O(length of the input); no allocation but the words vector. Thread-safe.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/status.h"

namespace soiq {

// Walks text line by line; a line ends at "\n" (a "\r" before it is dropped), the last one may end
// at the end of the text.
class LineReader {
 public:
  // `first_line` is the number the first line gets (a body after a header continues its count).
  explicit LineReader(std::string_view text, int64_t first_line = 1) : text_(text), next_number_(first_line) {}

  // The next line without its end of line; false when the text is used up.
  bool next(std::string_view& line);
  // The number of the line last returned by next().
  int64_t line_number() const { return next_number_ - 1; }
  // Bytes of the text consumed so far (the start of the line next() would return).
  size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  int64_t next_number_;
};

// The words of `line` (separated by spaces, tabs, CR, vertical tabs or form feeds) into `words`,
// which is cleared first; reusing one vector across lines avoids an allocation per line.
void words_of(std::string_view line, std::vector<std::string_view>& words);

// The whole token as a finite double ("1", "-2.5e3", "+.5"); std::from_chars, so no locale.
Result<double> finite_number(std::string_view token, std::string_view where);

// The whole token as a double that may be NaN or infinite, for values soiq ignores (STL normals).
Result<double> any_number(std::string_view token, std::string_view where);

// The whole token as a decimal integer ("12", "-3", "+4").
Result<int64_t> whole_integer(std::string_view token, std::string_view where);

// The token in single quotes for a message: at most 40 bytes ("..." marks a cut) and bytes that
// are not printable ASCII shown as '?', so hostile input cannot make messages huge or multi-line.
std::string quoted(std::string_view token);

// "<format> '<name>' line <n>", the prefix of every message about a line.
std::string line_where(std::string_view format, const std::string& name, int64_t line);

}  // namespace soiq
