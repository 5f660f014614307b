#include "proto/text/feature_expression.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

#include "core/base/did_you_mean.h"

namespace soiq::proto_text {

namespace {

using soiq::v1::ComparisonOp;
using soiq::v1::FeatureRef;
using soiq::v1::Predicate;

// A cursor over the text; every error names the column it stopped at.
class Parser {
 public:
  explicit Parser(const std::string& text) : text_(text) {}

  Status error(const std::string& what) const {
    return invalid_argument(what + " at column " + std::to_string(pos_ + 1) + " of '" + text_ + "'");
  }
  void skip_blanks() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool at_end() {
    skip_blanks();
    return pos_ == text_.size();
  }
  bool accept(const std::string& token) {
    skip_blanks();
    if (text_.compare(pos_, token.size(), token) != 0) return false;
    pos_ += token.size();
    return true;
  }
  // Characters satisfying `ok`, at least one.
  template <typename Ok>
  std::string take(Ok ok) {
    skip_blanks();
    const size_t from = pos_;
    while (pos_ < text_.size() && ok(text_[pos_])) ++pos_;
    return text_.substr(from, pos_ - from);
  }
  size_t pos() const { return pos_; }
  void set_pos(size_t p) { pos_ = p; }
  const std::string& text() const { return text_; }

 private:
  const std::string& text_;
  size_t pos_ = 0;
};

bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool region_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == ':' || c == '.' || c == '_'; }
bool image_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_'; }

Status check_region(const std::string& region, const Parser& p) {
  if (region == "inside") return ok_status();
  for (const char* kind : {"shell:", "core:"}) {
    const std::string prefix = kind;
    if (region.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string r = region.substr(prefix.size());
    char* end = nullptr;
    const double mm = std::strtod(r.c_str(), &end);
    if (r.empty() || *end != '\0' || !std::isfinite(mm) || !(mm > 0)) {
      return p.error("region '" + region + "' needs a radius > 0 mm, like " + prefix + "5");
    }
    return ok_status();
  }
  // Suggest with the reader's own radius, as core's parse_region does: "shel:5" means "shell:5".
  const size_t colon = region.find(':');
  const std::string radius = colon == std::string::npos ? "R" : region.substr(colon + 1);
  const std::string names[] = {"inside", "shell:" + radius, "core:" + radius};
  return p.error("unknown region '" + region + "'" + did_you_mean(region, names) + " (use inside, shell:R or core:R)");
}

Result<FeatureRef> parse_feature_at(Parser& p, bool inside_asym) {
  FeatureRef f;
  p.skip_blanks();
  const size_t start = p.pos();
  if (p.accept("asym")) {
    if (p.accept("(")) {
      if (inside_asym) {
        p.set_pos(start);
        return p.error("asym() cannot be nested");
      }
      SOIQ_ASSIGN_OR_RETURN(f, parse_feature_at(p, true));
      if (!p.accept(")")) return p.error("expected ')' closing asym(");
      f.set_asymmetry(true);
      return f;
    }
    p.set_pos(start);  // a feature whose name starts with "asym"
  }
  if (p.pos() >= p.text().size() || !std::isalpha(static_cast<unsigned char>(p.text()[p.pos()]))) {
    return p.error("expected a feature name");
  }
  f.set_name(p.take(name_char));
  if (!p.accept("[")) return f;
  p.skip_blanks();
  const size_t region_at = p.pos();
  const std::string region = p.take(region_char);
  if (!region.empty()) {
    const size_t after = p.pos();
    p.set_pos(region_at);
    SOIQ_RETURN_IF_ERROR(check_region(region, p));
    p.set_pos(after);
    f.set_region(region);
  }
  if (p.accept(",")) {
    const std::string image = p.take(image_char);
    if (image.empty()) return p.error("expected an image (a modality like PT or a series uid)");
    f.set_image(image);
  } else if (region.empty()) {
    return p.error("expected a region (inside, shell:R, core:R) or ',IMAGE'");
  }
  if (!p.accept("]")) return p.error("expected ']'");
  return f;
}

}  // namespace

Result<FeatureRef> parse_feature(const std::string& text) {
  Parser p(text);
  SOIQ_ASSIGN_OR_RETURN(FeatureRef f, parse_feature_at(p, false));
  if (!p.at_end()) return p.error("unexpected text after the feature");
  return f;
}

Result<Predicate> parse_predicate(const std::string& text) {
  Parser p(text);
  Predicate predicate;
  SOIQ_ASSIGN_OR_RETURN(*predicate.mutable_feature(), parse_feature_at(p, false));
  // Two-character operators first, so "<=" is not read as "<" then "=".
  bool found = false;
  for (const size_t length : {2, 1}) {
    for (const Comparison c : kComparisons) {
      const std::string_view symbol = comparison_symbol(c);
      if (found || symbol.size() != length || !p.accept(std::string(symbol))) continue;
      predicate.set_op(proto_comparison(c));
      found = true;
    }
  }
  if (!found) {
    return p.error(p.at_end() ? "expected a comparison (< <= > >= == !=) and a number"
                              : "expected a comparison (< <= > >= == !=)");
  }
  p.skip_blanks();
  const std::string rest = p.text().substr(p.pos());
  std::string number = rest;
  while (!number.empty() && std::isspace(static_cast<unsigned char>(number.back()))) number.pop_back();
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || !std::isfinite(v)) return p.error("expected a number");
  predicate.set_value(v);
  return predicate;
}

std::string feature_text(const FeatureRef& f) {
  std::string text = f.name();
  if (!f.region().empty() || !f.image().empty()) {
    text += "[" + f.region() + (f.image().empty() ? "" : "," + f.image()) + "]";
  }
  return f.asymmetry() ? "asym(" + text + ")" : text;
}

std::optional<Comparison> comparison_of(ComparisonOp op) {
  switch (op) {
    case soiq::v1::LT:
      return Comparison::kLess;
    case soiq::v1::LE:
      return Comparison::kLessOrEqual;
    case soiq::v1::GT:
      return Comparison::kGreater;
    case soiq::v1::GE:
      return Comparison::kGreaterOrEqual;
    case soiq::v1::EQ:
      return Comparison::kEqual;
    case soiq::v1::NE:
      return Comparison::kNotEqual;
    default:
      return std::nullopt;
  }
}

ComparisonOp proto_comparison(Comparison op) {
  for (const int value : {soiq::v1::LT, soiq::v1::LE, soiq::v1::GT, soiq::v1::GE, soiq::v1::EQ, soiq::v1::NE}) {
    if (comparison_of(ComparisonOp(value)) == op) return ComparisonOp(value);
  }
  return soiq::v1::COMPARISON_OP_UNSPECIFIED;
}

const char* comparison_text(ComparisonOp op) {
  const std::optional<Comparison> c = comparison_of(op);
  return c ? comparison_symbol(*c) : "?";
}

}  // namespace soiq::proto_text
