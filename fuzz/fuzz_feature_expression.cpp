// Feeds each input, as text, to the query expression parsers: parse_feature and parse_predicate
// (proto/text/feature_expression.h; `soiq query --where/--select/--order-by`, soiqd's /soiq/v1/query) and parse_region
// (core/regions/regions.h; the region of every feature a query names, which soiqd parses from the request).
// A bug is any crash or sanitizer report, a run over -timeout, or a broken round trip: a feature
// parse_feature accepts must come back from feature_text as text parse_feature reads to the same
// feature, and a region parse_region accepts likewise through region_name.

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/regions/regions.h"
#include "fuzz/require.h"
#include "proto/text/feature_expression.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);

  auto feature = soiq::proto_text::parse_feature(text);
  if (feature.ok()) {
    auto again = soiq::proto_text::parse_feature(soiq::proto_text::feature_text(*feature));
    soiq::fuzz::require(again.ok(), "parse_feature refused feature_text of a feature it accepted");
    soiq::fuzz::require(again->SerializeAsString() == feature->SerializeAsString(),
                        "parse_feature(feature_text(f)) differs from f");
  }

  auto predicate = soiq::proto_text::parse_predicate(text);
  if (predicate.ok()) (void)soiq::proto_text::comparison_text(predicate->op());

  auto region = soiq::parse_region(text);
  if (region.ok()) {
    auto again = soiq::parse_region(soiq::region_name(*region));
    soiq::fuzz::require(again.ok(), "parse_region refused region_name of a region it accepted");
    soiq::fuzz::require(again->kind == region->kind && again->radius_mm == region->radius_mm,
                        "parse_region(region_name(r)) differs from r");
  }
  return 0;
}
