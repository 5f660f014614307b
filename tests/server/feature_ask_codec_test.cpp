// The text a query hands to other replicas for its structures: every FeatureAsk reads back equal,
// and damaged or foreign text is DATA_LOSS, never a different computation.
#include "server/app/feature_ask_codec.h"

#include <gtest/gtest.h>

namespace soiq::server {
namespace {

bool same(const FeatureAsk& a, const FeatureAsk& b) {
  if (a.names != b.names || a.images != b.images || a.interpolation != b.interpolation || a.fill_rule != b.fill_rule ||
      a.regions.size() != b.regions.size())
    return false;
  for (size_t i = 0; i < a.regions.size(); ++i) {
    if (a.regions[i].kind != b.regions[i].kind || a.regions[i].radius_mm != b.regions[i].radius_mm) return false;
  }
  return a.grid.kind == b.grid.kind && a.grid.spacing_mm[0] == b.grid.spacing_mm[0] &&
         a.grid.spacing_mm[1] == b.grid.spacing_mm[1] && a.grid.spacing_mm[2] == b.grid.spacing_mm[2] &&
         a.grid.margin_voxels == b.grid.margin_voxels && a.grid.series == b.grid.series;
}

TEST(FeatureAskCodec, EveryFieldReadsBackExactly) {
  FeatureAsk ask;
  ask.names = {"voxel_volume_mm3", "mean", "odd,name=with%chars\n"};
  ask.regions = {RegionSpec{RegionKind::kInside, 0}, RegionSpec{RegionKind::kShell, 1.0000001},
                 RegionSpec{RegionKind::kCore, 2.5}};
  ask.images = {"CT", "1.2.840.10008.5.1.4.1.1.2", ""};
  ask.interpolation = Interpolation::kLinear;
  ask.grid.kind = GridChoice::Kind::kSeriesModality;
  ask.grid.spacing_mm = {0.1, 1.0 / 3.0, 2e-7};
  ask.grid.margin_voxels = 7;
  ask.grid.series = "PT,=%";
  ask.fill_rule = FillRule::kEvenOdd;
  Result<FeatureAsk> back = decode_feature_ask(encode_feature_ask(ask));
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  EXPECT_TRUE(same(ask, *back)) << encode_feature_ask(ask);
  Result<FeatureAsk> plain = decode_feature_ask(encode_feature_ask(FeatureAsk{}));
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(same(FeatureAsk{}, *plain));
}

TEST(FeatureAskCodec, DamagedOrForeignTextIsDataLoss) {
  const std::string good = encode_feature_ask(FeatureAsk{});
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  for (const std::string& bad :
       {std::string(), std::string("soiq-feature-ask-2\n"), good.substr(0, good.size() - 1),
        replaced("grid=axis", "grid=polar"), replaced("fill=nonzero", "fill=maybe"), replaced("margin=2", "margin=2.5"),
        replaced("names=", "names=%G1"), replaced("interpolation=nearest", "interpolation=cubic"), good + "extra=1\n",
        replaced("margin=2\n", "")}) {
    const Result<FeatureAsk> r = decode_feature_ask(bad);
    EXPECT_EQ(r.status().code(), StatusCode::kDataLoss) << bad;
  }
}

}  // namespace
}  // namespace soiq::server
