// The original DICOM instances a series keeps (NewSeries::instances, list_instances,
// get_instance_file), on every backend: stored and read back as sent, a file stored once however
// many instances hold it, kept when the same series comes again (and added when it lacked them),
// swapped when the series is replaced, gone with the patient, and every malformed instance refused
// before anything is stored. Damaged bytes and older schemas: store_instances_damage_test.cpp.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "db/store.h"
#include "tests/db/store_backends.h"
#include "tests/db/store_fixture.h"
#include "tests/db/store_inputs.h"
#include "tests/db/temp_store.h"

namespace soiq::db {
namespace {

using testing::contains;
using testing::instance_file_bytes;
using testing::instance_of;
using testing::series_with_instances;
using testing::slice_uid;

constexpr char kSeries[] = "1.2.3.4";

void expect_instance(const InstanceRecord& got, const InstanceRecord& want) {
  EXPECT_EQ(got.sop_instance_uid, want.sop_instance_uid);
  EXPECT_EQ(got.series_uid, want.series_uid);
  EXPECT_EQ(got.slice, want.slice);
  EXPECT_EQ(got.file_sha256, want.file_sha256);
  EXPECT_EQ(got.file_bytes, want.file_bytes);
  EXPECT_EQ(got.metadata, want.metadata);
}

template <typename Backend>
class StoreInstances : public testing::StoreTest<Backend> {
 protected:
  std::vector<InstanceRecord> listed(const std::string& series_uid) {
    auto got = this->records().list_instances(series_uid);
    EXPECT_TRUE(got.ok()) << got.status().to_string();
    return got.ok() ? *got : std::vector<InstanceRecord>{};
  }
};
TYPED_TEST_SUITE(StoreInstances, testing::StoreBackends, testing::StoreBackendNames);

TYPED_TEST(StoreInstances, TheInstancesAreListedBackFieldForFieldInSliceOrderWithTheirFiles) {
  NewSeries s = series_with_instances("P1", kSeries, 1.0f);
  std::swap(s.instances[0], s.instances[2]);  // sent in another order than their slices'
  ASSERT_TRUE(this->records().put_series(s).ok());
  const std::vector<InstanceRecord> got = this->listed(kSeries);
  ASSERT_EQ(got.size(), 3u);
  int64_t bytes = 0;
  for (int k = 0; k < 3; ++k) {
    const NewInstance& sent = s.instances[size_t(2 - k)];
    expect_instance(got[size_t(k)], sent.record);
    auto file = this->records().get_instance_file(got[size_t(k)].file_sha256);
    ASSERT_TRUE(file.ok()) << file.status().to_string();
    EXPECT_EQ(*file, sent.file);
    bytes += int64_t(sent.file.size());
  }
  const Counts n = this->counts();
  EXPECT_EQ(n.instances, 3);
  EXPECT_EQ(n.instance_files, 3);
  EXPECT_EQ(n.instance_bytes, bytes);
}

TYPED_TEST(StoreInstances, AnInstanceFileStoredOnceIsSharedAndGoesWithItsLastInstance) {
  const std::string same = instance_file_bytes("any", 0);
  NewSeries a = series_with_instances("P1", "1.2.3.4", 1.0f, /*kept=*/false);
  NewSeries b = series_with_instances("P2", "1.2.3.5", 2.0f, /*kept=*/false);
  a.instances.push_back(instance_of("1.2.3.4", 0, same));
  b.instances.push_back(instance_of("1.2.3.5", 1, same));
  ASSERT_TRUE(this->records().put_series(a).ok());
  ASSERT_TRUE(this->records().put_series(b).ok());
  Counts n = this->counts();
  EXPECT_EQ(n.instances, 2);
  EXPECT_EQ(n.instance_files, 1);
  EXPECT_EQ(n.instance_bytes, int64_t(same.size()));

  ASSERT_TRUE(this->records().delete_patient("P1").ok());
  n = this->counts();
  EXPECT_EQ(n.instances, 1);
  EXPECT_EQ(n.instance_files, 1);  // P2's instance still holds it
  EXPECT_EQ(*this->records().get_instance_file(a.instances[0].record.file_sha256), same);
  ASSERT_TRUE(this->records().delete_patient("P2").ok());
  EXPECT_EQ(this->counts().instance_files, 0);
}

TYPED_TEST(StoreInstances, TheSameSeriesSentAgainKeepsItsInstancesAndGetsTheOnesItLacked) {
  ASSERT_TRUE(this->records().put_series(series_with_instances("P1", kSeries, 1.0f)).ok());
  for (const bool replace : {true, false}) {
    NewSeries again = series_with_instances("P1", kSeries, 1.0f, /*kept=*/false);
    again.replace_other_content = replace;
    ASSERT_TRUE(this->records().put_series(again).ok());
    EXPECT_EQ(this->listed(kSeries).size(), 3u) << "replace_other_content " << replace;
  }

  // Stored before instances were kept (or with some of them): imported again, it gets the others.
  NewSeries partly = series_with_instances("P1", "1.2.3.5", 2.0f);
  partly.instances.resize(1);
  ASSERT_TRUE(this->records().put_series(partly).ok());
  ASSERT_EQ(this->listed("1.2.3.5").size(), 1u);
  NewSeries whole = series_with_instances("P1", "1.2.3.5", 2.0f);
  whole.replace_other_content = false;  // as a DICOM import sends it
  ASSERT_TRUE(this->records().put_series(whole).ok());
  const std::vector<InstanceRecord> got = this->listed("1.2.3.5");
  ASSERT_EQ(got.size(), 3u);
  for (int k = 0; k < 3; ++k) expect_instance(got[size_t(k)], whole.instances[size_t(k)].record);
  EXPECT_EQ(this->counts().instances, 6);
}

TYPED_TEST(StoreInstances, AReplacedSeriesSwapsItsInstancesAndItsFilesNobodyHoldsGo) {
  const NewSeries first = series_with_instances("P1", kSeries, 1.0f, true, /*version=*/1);
  ASSERT_TRUE(this->records().put_series(first).ok());
  NewSeries other = series_with_instances("P1", kSeries, 5.0f, true, /*version=*/2);  // other voxels
  other.replace_other_content = false;
  EXPECT_EQ(this->records().put_series(other).status().code(), StatusCode::kAlreadyExists);
  EXPECT_EQ(this->listed(kSeries)[0].file_sha256, first.instances[0].record.file_sha256);

  other.replace_other_content = true;
  auto replaced = this->records().put_series(other);
  ASSERT_TRUE(replaced.ok()) << replaced.status().to_string();
  EXPECT_TRUE(*replaced);
  const std::vector<InstanceRecord> got = this->listed(kSeries);
  ASSERT_EQ(got.size(), 3u);
  int64_t bytes = 0;
  for (int k = 0; k < 3; ++k) {
    expect_instance(got[size_t(k)], other.instances[size_t(k)].record);
    bytes += int64_t(other.instances[size_t(k)].file.size());
    EXPECT_EQ(this->records().get_instance_file(first.instances[size_t(k)].record.file_sha256).status().code(),
              StatusCode::kNotFound);
  }
  const Counts n = this->counts();
  EXPECT_EQ(n.instances, 3);
  EXPECT_EQ(n.instance_files, 3);
  EXPECT_EQ(n.instance_bytes, bytes);
}

TYPED_TEST(StoreInstances, DeletingThePatientDeletesItsInstancesAndTheirFiles) {
  ASSERT_TRUE(this->records().put_series(series_with_instances("P1", kSeries, 1.0f)).ok());
  ASSERT_TRUE(this->records().put_series(series_with_instances("P1", "1.2.3.5", 2.0f)).ok());
  ASSERT_EQ(this->counts().instance_files, 6);
  ASSERT_TRUE(this->records().delete_patient("P1").ok());
  const Counts n = this->counts();
  EXPECT_EQ(n.instances, 0);
  EXPECT_EQ(n.instance_files, 0);
  EXPECT_EQ(n.instance_bytes, 0);
}

TYPED_TEST(StoreInstances, EachMalformedInstanceIsRefusedNamingItAndNothingIsStored) {
  struct Case {
    const char* what;
    std::function<void(NewSeries&)> spoil;
    std::string named;  // the instance the message names
  };
  const std::string second = slice_uid(kSeries, 1);
  const std::vector<Case> cases = {
      {"unknown SOP Instance UID", [](NewSeries& s) { s.instances[1].record.sop_instance_uid = "1.2.3.4.99"; },
       "1.2.3.4.99"},
      {"wrong sha256", [](NewSeries& s) { s.instances[1].record.file_sha256 = s.instances[0].record.file_sha256; },
       second},
      {"slice after the last", [](NewSeries& s) { s.instances[1].record.slice = 3; }, second},
      {"negative slice", [](NewSeries& s) { s.instances[1].record.slice = -1; }, second},
      {"the same uid twice", [](NewSeries& s) { s.instances.push_back(s.instances[1]); }, second},
      {"empty metadata", [](NewSeries& s) { s.instances[1].record.metadata = ""; }, second},
      {"metadata not an object", [](NewSeries& s) { s.instances[1].record.metadata = "[]"; }, second},
      {"wrong size", [](NewSeries& s) { s.instances[1].record.file_bytes += 1; }, second},
      {"another series", [](NewSeries& s) { s.instances[1].record.series_uid = "1.2.3.5"; }, second},
      {"empty file", [](NewSeries& s) { s.instances[1] = instance_of(kSeries, 1, ""); }, second},
  };
  for (const Case& c : cases) {
    NewSeries s = series_with_instances("P1", kSeries, 1.0f);
    c.spoil(s);
    const Status refused = this->records().put_series(s).status();
    EXPECT_EQ(refused.code(), StatusCode::kInvalidArgument) << c.what << ": " << refused.to_string();
    EXPECT_TRUE(contains(refused.message(), "instance '" + c.named + "'")) << c.what << ": " << refused.message();
    const Counts n = this->counts();
    EXPECT_EQ(n.series, 0) << c.what;
    EXPECT_EQ(n.instances, 0) << c.what;
    EXPECT_EQ(n.instance_files, 0) << c.what;
  }
}

TYPED_TEST(StoreInstances, AnInstanceOfAnotherSeriesIsRefusedAndLeavesNothing) {
  ASSERT_TRUE(this->records().put_series(series_with_instances("P1", kSeries, 1.0f)).ok());
  const Counts before = this->counts();
  // A series claiming the first one's slice 0 instance.
  NewSeries thief = series_with_instances("P1", "1.2.3.5", 2.0f);
  thief.series.slice_instance_uids[0] = slice_uid(kSeries, 0);
  thief.instances[0] = instance_of(kSeries, 0, instance_file_bytes("thief", 0));
  thief.instances[0].record.series_uid = "1.2.3.5";
  const Status refused = this->records().put_series(thief).status();
  EXPECT_EQ(refused.code(), StatusCode::kFailedPrecondition) << refused.to_string();
  EXPECT_TRUE(contains(refused.message(), "instance '1.2.3.4.1' belongs to series '1.2.3.4'")) << refused.message();
  const Counts after = this->counts();
  EXPECT_EQ(after.series, before.series);
  EXPECT_EQ(after.instances, before.instances);
  EXPECT_EQ(after.instance_files, before.instance_files);
}

TYPED_TEST(StoreInstances, AnUnknownSeriesIsNotFoundAndOneThatKeptNoneListsNone) {
  const auto unknown = this->records().list_instances("9.9.9");
  EXPECT_EQ(unknown.status().code(), StatusCode::kNotFound);
  EXPECT_TRUE(contains(unknown.status().message(), "'9.9.9'")) << unknown.status().message();
  ASSERT_TRUE(this->records().put_series(series_with_instances("P1", kSeries, 1.0f, /*kept=*/false)).ok());
  EXPECT_TRUE(this->listed(kSeries).empty());
  const std::string absent(64, 'a');
  const auto file = this->records().get_instance_file(absent);
  EXPECT_EQ(file.status().code(), StatusCode::kNotFound);
  EXPECT_TRUE(contains(file.status().message(), absent)) << file.status().message();
}

}  // namespace
}  // namespace soiq::db
