#pragma once
// How `soiq features` prints a feature report, offline or from soiqd (one code path for both):
//   table  "[shape]" then one block per region / image, "  name  value", then "[timings, ms]"
//   json   one object: shape features by name, intensity ones nested under "intensity" -> region ->
//          image, then "timings_ms"
//   csv    "region,image,feature,value", one row per feature (array values joined by ';')
// Numbers print with %.10g; NaN and infinities as null.

#include <string>

#include "core/features/structure_features.h"

namespace soiq::cli {

// `format` is table, json or csv (anything else prints the table).
void print_feature_report(const FeatureReport& report, const std::string& format);

}  // namespace soiq::cli
