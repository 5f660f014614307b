// Stable UIDs of a structure's SEG and RT Structure Set (server/app/structure_object_uids.h): the
// same structure, surface and object give the same UIDs, another surface, structure or object
// others, and a UID gives back its structure id, object and kind; anything else is not one of them.
#include "server/app/structure_object_uids.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>

namespace soiq::server {
namespace {

using db::StructureObject;

db::StructureRecord structure(int64_t id, char surface) {
  db::StructureRecord s;
  s.id = id;
  s.name = "GTV";
  s.source_series_uid = "1.2.3";
  s.surface.sha256 = std::string(64, surface);
  return s;
}

TEST(StructureObjectUids, StableForTheSameContentAndDifferentOtherwise) {
  for (const StructureObject o : db::kStructureObjects) {
    const StructureObjectUids a = structure_object_uids(structure(7, 'a'), o);
    EXPECT_EQ(a.series_uid, structure_object_uids(structure(7, 'a'), o).series_uid);
    EXPECT_NE(a.series_uid, a.sop_instance_uid);
    EXPECT_NE(a.series_uid, structure_object_uids(structure(7, 'b'), o).series_uid);  // a new surface
    EXPECT_NE(a.series_uid, structure_object_uids(structure(8, 'a'), o).series_uid);
  }
}

TEST(StructureObjectUids, TheRtStructureSetsDifferFromTheSegs) {
  const StructureObjectUids seg = structure_object_uids(structure(7, 'a'), StructureObject::kSeg);
  const StructureObjectUids rt = structure_object_uids(structure(7, 'a'), StructureObject::kRtStruct);
  for (const std::string& uid : {rt.series_uid, rt.sop_instance_uid}) {
    EXPECT_NE(uid, seg.series_uid);
    EXPECT_NE(uid, seg.sop_instance_uid);
  }
}

// The SEG's UIDs are the ones soiq gave before it served RT Structure Sets (computed then), so a
// SEG a PACS or viewer holds still resolves.
TEST(StructureObjectUids, TheSegKeepsItsEarlierUids) {
  const StructureObjectUids seg = structure_object_uids(structure(7, 'a'), StructureObject::kSeg);
  EXPECT_EQ(seg.series_uid, "2.25.9103204590188061079413984");
  EXPECT_EQ(seg.sop_instance_uid, "2.25.9140983522051018241123552");
}

TEST(StructureObjectUids, ParsedBackToStructureObjectAndKind) {
  // PS3.5 B.2: 2.25 and a decimal integer without leading zeros, within UI's 64 characters (checked
  // by hand: std::regex trips GCC 12's -Wmaybe-uninitialized in the sanitizer build).
  for (const StructureObject o : db::kStructureObjects) {
    for (const int64_t id : {int64_t(1), int64_t(123456), (int64_t(1) << 47) - 1}) {
      const StructureObjectUids u = structure_object_uids(structure(id, 'c'), o);
      for (const std::string& uid : {u.series_uid, u.sop_instance_uid}) {
        EXPECT_EQ(uid.rfind("2.25.", 0), 0u) << uid;
        const std::string digits = uid.substr(5);
        EXPECT_TRUE(!digits.empty() && digits[0] != '0' &&
                    std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); }))
            << uid;
        EXPECT_LE(uid.size(), 64u);
      }
      const std::optional<ParsedStructureUid> series = parse_structure_object_uid(u.series_uid);
      const std::optional<ParsedStructureUid> instance = parse_structure_object_uid(u.sop_instance_uid);
      ASSERT_TRUE(series && instance) << u.series_uid;
      EXPECT_EQ(series->structure_id, id);
      EXPECT_EQ(instance->structure_id, id);
      EXPECT_EQ(series->object, o);
      EXPECT_EQ(instance->object, o);
      EXPECT_FALSE(series->instance);
      EXPECT_TRUE(instance->instance);
    }
  }
}

TEST(StructureObjectUids, OtherUidsAreNotParsed) {
  for (const char* uid : {"1.2.840.10008.1", "2.25.", "2.25.0", "2.25.012", "2.25.12a",
                          "2.25.329800735698586629295641978511506172918",  // a version-4 UUID
                          "2.25.999999999999999999999999999999999999999999"})
    EXPECT_FALSE(parse_structure_object_uid(uid)) << uid;
  // An id past 2^47 - 1 gets UIDs nothing resolves.
  EXPECT_FALSE(parse_structure_object_uid(
      structure_object_uids(structure(int64_t(1) << 47, 'c'), StructureObject::kSeg).series_uid));
}

}  // namespace
}  // namespace soiq::server
