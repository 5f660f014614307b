// SqlStore::import_batch: the series and structures of one DICOM import in one write
// transaction, so an import is stored whole or not at all.
#include <utility>

#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"
#include "db/validate_records.h"

namespace soiq::db {

Result<ImportedBatch> SqlStore::import_batch(const ImportBatch& b) {
  for (const NewSeries& s : b.series) SOIQ_RETURN_IF_ERROR(validate_new_series(s));
  for (const NewStructure& s : b.structures) SOIQ_RETURN_IF_ERROR(validate_new_structure(s));
  ImportedBatch out;
  SOIQ_RETURN_IF_ERROR(write([&](SqlSession& c) -> Status {
    out = {};  // write() may run this again after ABORTED
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
