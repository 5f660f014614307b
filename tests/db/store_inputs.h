#pragma once
// Store inputs that the typed store tests and the SQLite-only tests of the same topic both use
// (the SQLite ones add a trigger, or take the file back to an older schema first).

#include "db/store.h"
#include "tests/db/temp_store.h"

namespace soiq::db::testing {

// Two series (CT and PT) and two structures of one study: an import's usual shape.
inline ImportBatch two_series_two_structures() {
  ImportBatch b;
  b.series.push_back(new_series("P1", "S1", "SE-CT", 1.0f));
  b.series.push_back(new_series("P1", "S1", "SE-PT", 2.0f));
  b.series[1].series.modality = "PT";
  b.structures.push_back(new_structure("P1", "S1", "GTV_CT", 1.0));
  b.structures.push_back(new_structure("P1", "S1", "GTV_PT", 2.0));
  return b;
}

// A series whose study has DICOM's Study Time, Study ID and Accession Number.
inline NewSeries series_of_identified_study() {
  NewSeries s = new_series("P1", "1.2.3", "1.2.3.4", 1.0f);
  s.study.study_time = "101512.5";
  s.study.study_id = "S-17";
  s.study.accession_number = "ACC0042";
  return s;
}

// An RT Structure Set's ROI: its source series and its source uid.
inline NewStructure imported_structure(const std::string& name, double surface_offset) {
  NewStructure s = new_structure("P1", "1.2.3", name, surface_offset);
  s.source_series_uid = "1.2.3.4";
  s.source_uid = "1.2.3.77/1";
  return s;
}

}  // namespace soiq::db::testing
