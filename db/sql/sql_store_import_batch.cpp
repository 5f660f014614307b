// SqlStore::import_batch: the series and structures of one DICOM import in one write
// transaction, so an import is stored whole or not at all.
#include <map>
#include <set>
#include <string>
#include <utility>

#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

constexpr char kStructuresOfObjectSql[] = R"sql(
  SELECT id, name, source_uid FROM structures WHERE source_uid >= ?1 AND source_uid < ?2 ORDER BY source_uid)sql";

// A DICOM object (RT Structure Set, SEG) sent again must hold every ROI stored from it: one that
// is stored but not sent means the object sent is another content under the same UID.
Status check_no_roi_missing(SqlSession& c, const ImportBatch& b) {
  std::map<std::string, std::set<std::string>> sent;  // SOP Instance UID -> source_uids sent
  for (const NewStructure& s : b.structures) {
    const size_t slash = s.source_uid.rfind('/');
    if (s.replace_other_content || slash == std::string::npos) continue;
    sent[s.source_uid.substr(0, slash)].insert(s.source_uid);
  }
  for (const auto& [sop, uids] : sent) {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kStructuresOfObjectSql));
    q.bind(1, sop + "/");
    q.bind(2, sop + "0");  // '0' follows '/': every source_uid of this object lies between
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      const std::string source = q.text(2);
      if (uids.count(source) > 0) continue;
      return Status(StatusCode::kAlreadyExists,
                    "DICOM object '" + sop + "' is stored with ROI " + source.substr(sop.size() + 1) + " ('" +
                        q.text(1) + "', structure " + std::to_string(q.int64(0)) +
                        "), which the object sent does not hold; a DICOM UID names one content: send the object as "
                        "stored, or replace it (soiq import --replace)");
    }
  }
  return ok_status();
}

}  // namespace

Result<ImportedBatch> SqlStore::import_batch(const ImportBatch& b) {
  for (const NewSeries& s : b.series) SOIQ_RETURN_IF_ERROR(validate_new_series(s));
  for (const NewStructure& s : b.structures) SOIQ_RETURN_IF_ERROR(validate_new_structure(s));
  ImportedBatch out;
  SOIQ_RETURN_IF_ERROR(write([&](SqlSession& c) -> Status {
    out = {};  // write() may run this again after ABORTED
    SOIQ_RETURN_IF_ERROR(check_no_roi_missing(c, b));
    // Series first: a structure's study then already has its series' modalities for stage 1.
    for (const NewSeries& s : b.series) {
      SOIQ_ASSIGN_OR_RETURN(const bool replaced, insert_series(c, s));
      out.series_replaced.push_back(replaced);
    }
    for (const NewStructure& s : b.structures) {
      SOIQ_ASSIGN_OR_RETURN(AddedStructure added, insert_structure(c, s));
      out.structures.push_back(std::move(added));
    }
    return ok_status();
  }));
  return out;
}

}  // namespace soiq::db
