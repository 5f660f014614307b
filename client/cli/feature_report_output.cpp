#include "client/cli/feature_report_output.h"

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "proto/text/query_columns.h"

namespace soiq::cli {

namespace {

// soiq's one way of writing a number (%.10g, "null" for NaN and infinities).
std::string number(double v) { return proto_text::number_text(v); }

std::string value_text(const std::vector<double>& v, const char* open, const char* sep, const char* close) {
  if (v.size() == 1) return number(v[0]);
  std::string out = open;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + number(v[i]);
  return out + close;
}

void print_json(const FeatureReport& r) {
  std::string out = "{";
  bool first = true;
  auto key = [&](const std::string& k) {
    out += (first ? "\"" : ", \"") + k + "\": ";
    first = false;
  };
  for (const Feature& f : r.features) {
    if (!f.region.empty()) continue;
    key(f.name);
    out += value_text(f.value, "[", ", ", "]");
  }
  // Intensity features nest under their region, then their image.
  std::map<std::string, std::map<std::string, std::vector<const Feature*>>> nested;
  std::vector<std::string> region_order;
  for (const Feature& f : r.features) {
    if (f.region.empty()) continue;
    if (!nested.count(f.region)) region_order.push_back(f.region);
    nested[f.region][f.image].push_back(&f);
  }
  if (!nested.empty()) {
    key("intensity");
    out += "{";
    for (size_t ri = 0; ri < region_order.size(); ++ri) {
      out += (ri ? ", \"" : "\"") + region_order[ri] + "\": {";
      size_t ii = 0;
      for (const auto& [image, features] : nested[region_order[ri]]) {
        out += (ii++ ? ", \"" : "\"") + image + "\": {";
        for (size_t fi = 0; fi < features.size(); ++fi) {
          out += (fi ? ", \"" : "\"") + features[fi]->name + "\": " + value_text(features[fi]->value, "[", ", ", "]");
        }
        out += "}";
      }
      out += "}";
    }
    out += "}";
  }
  key("timings_ms");
  out += "{";
  for (size_t i = 0; i < r.timings_ms.size(); ++i) {
    out += (i ? ", \"" : "\"") + r.timings_ms[i].first + "\": " + number(r.timings_ms[i].second);
  }
  out += "}}";
  std::puts(out.c_str());
}

void print_csv(const FeatureReport& r) {
  std::fputs(proto_text::csv_line({"region", "image", "feature", "value"}).c_str(), stdout);
  for (const Feature& f : r.features)
    std::fputs(proto_text::csv_line({f.region, f.image, f.name, value_text(f.value, "", ";", "")}).c_str(), stdout);
}

void print_table(const FeatureReport& r) {
  std::string block = "-";
  for (const Feature& f : r.features) {
    const std::string here = f.region.empty() ? "shape" : f.region + " / " + f.image;
    if (here != block) {
      std::printf("%s[%s]\n", block == "-" ? "" : "\n", here.c_str());
      block = here;
    }
    std::printf("  %-32s %s\n", f.name.c_str(), value_text(f.value, "(", ", ", ")").c_str());
  }
  std::printf("\n[timings, ms]\n");
  for (const auto& [part, ms] : r.timings_ms) std::printf("  %-32s %.2f\n", part.c_str(), ms);
}

}  // namespace

void print_feature_report(const FeatureReport& report, const std::string& format) {
  if (format == "json") {
    print_json(report);
  } else if (format == "csv") {
    print_csv(report);
  } else {
    print_table(report);
  }
}

}  // namespace soiq::cli
