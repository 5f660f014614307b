// A cached feature value's stored bytes (db/cached_value.h): float64s and a CRC-32 over key, entry
// and values; every flipped bit of them refused; the checksum covers what the value is stored
// under; values stored before the checksum still read.
#include "db/cached_value.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace soiq::db {
namespace {

CachedFeature value_of(std::vector<double> v) { return {"v7|0123abcd|grid 1 1 1|nonzero", "surface_area_mm2", v}; }

// Bitwise: == would take -0.0 for +0.0 and refuse NaN.
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

TEST(CachedValue, ValuesRoundTripBitwiseWithTheirChecksum) {
  for (const std::vector<double>& v : {std::vector<double>{}, std::vector<double>{1.0 / 3.0},
                                       std::vector<double>{-0.0, std::numeric_limits<double>::quiet_NaN(), 1e300}}) {
    const CachedFeature f = value_of(v);
    const std::string bytes = cached_value_bytes(f);
    EXPECT_EQ(bytes.size(), v.size() * 8 + 4);
    EXPECT_TRUE(cached_value_has_checksum(bytes));
    CachedFeature back{f.key, f.entry, {}};
    ASSERT_TRUE(set_cached_value(back, bytes).ok());
    EXPECT_TRUE(same_bits(back.value, v));
  }
}

TEST(CachedValue, EveryFlippedBitIsDataLossNamingTheKeyAndEntry) {
  const CachedFeature f = value_of({12.5, -3.25});
  std::string bytes = cached_value_bytes(f);
  for (size_t at = 0; at < bytes.size(); ++at) {
    for (int bit = 0; bit < 8; ++bit) {
      bytes[at] = char(bytes[at] ^ (1 << bit));
      CachedFeature back{f.key, f.entry, {}};
      const Status s = set_cached_value(back, bytes);
      bytes[at] = char(bytes[at] ^ (1 << bit));
      ASSERT_EQ(s.code(), StatusCode::kDataLoss) << "byte " << at << " bit " << bit;
      EXPECT_NE(s.message().find("checksum mismatch"), std::string::npos) << s.message();
      EXPECT_NE(s.message().find("'surface_area_mm2' under key '" + f.key + "'"), std::string::npos) << s.message();
      EXPECT_TRUE(back.value.empty());
    }
  }
}

// A value read under another key or entry than it was stored under (a flipped bit in the key: the
// value of another grid) is refused, and so is a character moved from the key to the entry.
TEST(CachedValue, TheChecksumCoversTheKeyAndEntryTheValueIsStoredUnder) {
  const CachedFeature f{"k1", "volume", {1.5}};
  const std::string bytes = cached_value_bytes(f);
  for (const CachedFeature& other :
       {CachedFeature{"k0", "volume", {}}, CachedFeature{"k1", "volumf", {}}, CachedFeature{"k", "1volume", {}}}) {
    CachedFeature back = other;
    EXPECT_EQ(set_cached_value(back, bytes).code(), StatusCode::kDataLoss) << other.key << " " << other.entry;
  }
}

TEST(CachedValue, AValueStoredBeforeTheChecksumStillReads) {
  const std::vector<double> v = {2.5, -0.0};
  const std::string old(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
  EXPECT_FALSE(cached_value_has_checksum(old));
  CachedFeature back{"k", "e", {}};
  ASSERT_TRUE(set_cached_value(back, old).ok());
  EXPECT_TRUE(same_bits(back.value, v));
  EXPECT_EQ(cached_value_damage(back, old), "");
}

TEST(CachedValue, ALengthOfNeitherFormIsDataLoss) {
  CachedFeature back{"k", "e", {}};
  const Status s = set_cached_value(back, std::string(13, 'x'));
  EXPECT_EQ(s.code(), StatusCode::kDataLoss);
  EXPECT_NE(s.message().find("13 bytes"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace soiq::db
