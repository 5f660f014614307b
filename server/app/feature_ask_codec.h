#pragma once
// A FeatureAsk as text, so a query can hand the computation of its structures to other soiqd
// replicas through the shared store (db::Stage2Work::ask; docs/SCALE_OUT.md), which compute
// exactly what it would: the same plan, the same cache key, the same entries.
//
// One field per line, "key=value", lists comma-separated, every element percent-encoded where it
// holds '%', ',', '=' or a control character. decode_feature_ask reads only what
// encode_feature_ask writes: DATA_LOSS naming the line for anything else (a row written by a newer
// soiqd, or damaged), so a replica computes nothing it does not understand.

#include <string>

#include "core/base/status.h"
#include "server/app/feature_engine.h"

namespace soiq::server {

std::string encode_feature_ask(const FeatureAsk& ask);
Result<FeatureAsk> decode_feature_ask(const std::string& text);

}  // namespace soiq::server
