// Stable UIDs of a structure's SEG (server/app/structure_seg_uids.h): the same structure and
// surface give the same UIDs, another surface or structure others, and a UID gives back its
// structure id and kind; anything else is not one of them.
#include "server/app/structure_seg_uids.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>

namespace soiq::server {
namespace {

db::StructureRecord structure(int64_t id, char surface) {
  db::StructureRecord s;
  s.id = id;
  s.name = "GTV";
  s.source_series_uid = "1.2.3";
  s.surface.sha256 = std::string(64, surface);
  return s;
}

TEST(StructureSegUids, StableForTheSameContentAndDifferentOtherwise) {
  const StructureSegUids a = structure_seg_uids(structure(7, 'a'));
  EXPECT_EQ(a.series_uid, structure_seg_uids(structure(7, 'a')).series_uid);
  EXPECT_NE(a.series_uid, a.sop_instance_uid);
  EXPECT_NE(a.series_uid, structure_seg_uids(structure(7, 'b')).series_uid);  // a new surface
  EXPECT_NE(a.series_uid, structure_seg_uids(structure(8, 'a')).series_uid);
  // PS3.5 B.2: 2.25 and a decimal integer without leading zeros, within UI's 64 characters (checked
  // by hand: std::regex trips GCC 12's -Wmaybe-uninitialized in the sanitizer build).
  for (const int64_t id : {int64_t(1), int64_t(123456), (int64_t(1) << 48) - 1}) {
    const StructureSegUids u = structure_seg_uids(structure(id, 'c'));
    for (const std::string& uid : {u.series_uid, u.sop_instance_uid}) {
      EXPECT_EQ(uid.rfind("2.25.", 0), 0u) << uid;
      const std::string digits = uid.substr(5);
      EXPECT_TRUE(!digits.empty() && digits[0] != '0' && std::all_of(digits.begin(), digits.end(), [](unsigned char c) {
        return std::isdigit(c);
      })) << uid;
      EXPECT_LE(uid.size(), 64u);
    }
    EXPECT_EQ(parse_structure_seg_uid(u.series_uid)->structure_id, id);
    EXPECT_FALSE(parse_structure_seg_uid(u.series_uid)->instance);
    EXPECT_TRUE(parse_structure_seg_uid(u.sop_instance_uid)->instance);
  }
}

TEST(StructureSegUids, OtherUidsAreNotParsed) {
  for (const char* uid : {"1.2.840.10008.1", "2.25.", "2.25.0", "2.25.012", "2.25.12a",
                          "2.25.329800735698586629295641978511506172918",  // a version-4 UUID
                          "2.25.999999999999999999999999999999999999999999"})
    EXPECT_FALSE(parse_structure_seg_uid(uid)) << uid;
}

}  // namespace
}  // namespace soiq::server
