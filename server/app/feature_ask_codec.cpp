#include "server/app/feature_ask_codec.h"

#include <charconv>
#include <cstdio>
#include <map>
#include <string_view>
#include <vector>

namespace soiq::server {
namespace {

// "v1": the first version of the encoding; a decoder refuses any other.
constexpr char kVersion[] = "soiq-feature-ask-1";

std::string escaped(std::string_view s) {
  std::string out;
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '%' || ch == ',' || ch == '=' || u < 0x20 || u == 0x7f) {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", u);
      out += hex;
    } else {
      out += ch;
    }
  }
  return out;
}

Result<std::string> unescaped(std::string_view s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      out += s[i];
      continue;
    }
    unsigned value = 0;
    if (i + 2 >= s.size() || std::from_chars(s.data() + i + 1, s.data() + i + 3, value, 16).ptr != s.data() + i + 3)
      return data_loss("a stage-2 ask has a bad escape in '" + std::string(s) + "'");
    out += char(value);
    i += 2;
  }
  return out;
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? "," : "") + escaped(items[i]);
  return out;
}

Result<std::vector<std::string>> split(std::string_view s) {
  std::vector<std::string> out;
  if (s.empty()) return out;
  for (size_t start = 0;;) {
    const size_t end = s.find(',', start);
    SOIQ_ASSIGN_OR_RETURN(std::string item,
                          unescaped(s.substr(start, end == std::string_view::npos ? end : end - start)));
    out.push_back(std::move(item));
    if (end == std::string_view::npos) return out;
    start = end + 1;
  }
}

std::string number(double v) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);  // exact
}

Result<double> parse_number(std::string_view s, const char* what) {
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return data_loss(std::string("a stage-2 ask has a bad ") + what);
  return v;
}

const char* grid_kind_name(GridChoice::Kind kind) {
  switch (kind) {
    case GridChoice::Kind::kAxisAligned:
      return "axis";
    case GridChoice::Kind::kSeriesUid:
      return "series_uid";
    case GridChoice::Kind::kSeriesModality:
      return "series_modality";
  }
  return "axis";
}

}  // namespace

std::string encode_feature_ask(const FeatureAsk& ask) {
  std::vector<std::string> regions;
  for (const RegionSpec& r : ask.regions) regions.push_back(region_name(r));
  std::string out = std::string(kVersion) + "\n";
  out += "names=" + joined(ask.names) + "\n";
  out += "regions=" + joined(regions) + "\n";
  out += "images=" + joined(ask.images) + "\n";
  out += std::string("interpolation=") + interpolation_name(ask.interpolation) + "\n";
  out += std::string("grid=") + grid_kind_name(ask.grid.kind) + "\n";
  out += "spacing=" + number(ask.grid.spacing_mm[0]) + "," + number(ask.grid.spacing_mm[1]) + "," +
         number(ask.grid.spacing_mm[2]) + "\n";
  out += "margin=" + std::to_string(ask.grid.margin_voxels) + "\n";
  out += "series=" + escaped(ask.grid.series) + "\n";
  out += std::string("fill=") + (ask.fill_rule == FillRule::kEvenOdd ? "evenodd" : "nonzero") + "\n";
  return out;
}

Result<FeatureAsk> decode_feature_ask(const std::string& text) {
  std::map<std::string, std::string> fields;
  size_t start = 0;
  bool first = true;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    if (end == std::string::npos) return data_loss("a stage-2 ask does not end its last line");
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    if (first) {
      if (line != kVersion) return data_loss("a stage-2 ask of another version: '" + line.substr(0, 40) + "'");
      first = false;
      continue;
    }
    const size_t eq = line.find('=');
    if (eq == std::string::npos || !fields.emplace(line.substr(0, eq), line.substr(eq + 1)).second)
      return data_loss("a stage-2 ask has a bad line '" + line.substr(0, 40) + "'");
  }
  static const char* kKeys[] = {"names",   "regions", "images", "interpolation", "grid",
                                "spacing", "margin",  "series", "fill"};
  if (first || fields.size() != std::size(kKeys)) return data_loss("a stage-2 ask lacks fields or has others");
  for (const char* key : kKeys)
    if (!fields.count(key)) return data_loss(std::string("a stage-2 ask lacks '") + key + "'");

  FeatureAsk ask;
  SOIQ_ASSIGN_OR_RETURN(ask.names, split(fields["names"]));
  SOIQ_ASSIGN_OR_RETURN(const std::vector<std::string> regions, split(fields["regions"]));
  for (const std::string& r : regions) {
    Result<RegionSpec> spec = parse_region(r);
    if (!spec.ok()) return data_loss("a stage-2 ask has a bad region: " + spec.status().message());
    ask.regions.push_back(*spec);
  }
  SOIQ_ASSIGN_OR_RETURN(ask.images, split(fields["images"]));
  const std::string& interpolation = fields["interpolation"];
  if (interpolation == interpolation_name(Interpolation::kNearest)) {
    ask.interpolation = Interpolation::kNearest;
  } else if (interpolation == interpolation_name(Interpolation::kLinear)) {
    ask.interpolation = Interpolation::kLinear;
  } else {
    return data_loss("a stage-2 ask has a bad interpolation '" + interpolation + "'");
  }
  const std::string& grid = fields["grid"];
  bool known_grid = false;
  for (const GridChoice::Kind kind :
       {GridChoice::Kind::kAxisAligned, GridChoice::Kind::kSeriesUid, GridChoice::Kind::kSeriesModality}) {
    if (grid == grid_kind_name(kind)) ask.grid.kind = kind, known_grid = true;
  }
  if (!known_grid) return data_loss("a stage-2 ask has a bad grid '" + grid + "'");
  SOIQ_ASSIGN_OR_RETURN(const std::vector<std::string> spacing, split(fields["spacing"]));
  if (spacing.size() != 3) return data_loss("a stage-2 ask has a bad spacing");
  for (int a = 0; a < 3; ++a) {
    SOIQ_ASSIGN_OR_RETURN(ask.grid.spacing_mm[a], parse_number(spacing[size_t(a)], "spacing"));
  }
  SOIQ_ASSIGN_OR_RETURN(const double margin, parse_number(fields["margin"], "margin"));
  ask.grid.margin_voxels = int(margin);
  if (double(ask.grid.margin_voxels) != margin) return data_loss("a stage-2 ask has a bad margin");
  SOIQ_ASSIGN_OR_RETURN(ask.grid.series, unescaped(fields["series"]));
  const std::string& fill = fields["fill"];
  if (fill != "nonzero" && fill != "evenodd") return data_loss("a stage-2 ask has a bad fill rule '" + fill + "'");
  ask.fill_rule = fill == "evenodd" ? FillRule::kEvenOdd : FillRule::kNonZero;
  return ask;
}

}  // namespace soiq::server
