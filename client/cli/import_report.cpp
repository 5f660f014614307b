#include "client/cli/import_report.h"

#include <cstdio>
#include <string>

#include "client/cli/row_printer.h"
#include "client/cli/show_records.h"

namespace soiq::cli {
namespace {

namespace v1 = soiq::v1;

std::string spacing_text(double x, double y, double z) {
  char text[96];
  std::snprintf(text, sizeof text, ", %.4g x %.4g x %.4g mm", x, y, z);
  return text;
}

std::string series_detail(const v1::Series& s) {
  const v1::ImageGeometry& g = s.geometry();
  std::string d = s.modality();
  if (g.dims_size() == 3 && g.spacing_size() == 3) {
    d += " " + std::to_string(g.dims(0)) + "x" + std::to_string(g.dims(1)) + "x" + std::to_string(g.dims(2)) +
         spacing_text(g.spacing(0), g.spacing(1), g.spacing(2)) + geometry_notes(g);
  }
  return d + ", study " + s.study_uid();
}

std::string study_detail(const v1::Study& s) {
  std::string d = s.study_date().empty() ? "no date" : s.study_date();
  if (s.has_age_years()) {
    char age[48];
    std::snprintf(age, sizeof age, ", age %.1f", s.age_years());
    d += age;
  }
  if (!s.description().empty()) d += ", " + s.description();
  return d;
}

void print_rows(const v1::ImportDicomResponse& r, const std::string& format) {
  RowPrinter out(format, {"what", "id", "patient", "detail"});
  for (const v1::Patient& p : r.patients()) {
    out.row({text_cell("patient"), text_cell(p.patient_id()), text_cell(p.patient_id()),
             text_cell("sex " + (p.sex().empty() ? std::string("?") : p.sex()) + ", born " +
                       (p.birth_date().empty() ? std::string("?") : p.birth_date()))});
  }
  for (const v1::Study& s : r.studies())
    out.row({text_cell("study"), text_cell(s.study_uid()), text_cell(s.patient_id()), text_cell(study_detail(s))});
  for (const v1::Series& s : r.series()) {
    std::string patient;
    for (const v1::Study& st : r.studies())
      if (st.study_uid() == s.study_uid()) patient = st.patient_id();
    out.row({text_cell("series"), text_cell(s.series_uid()), text_cell(patient), text_cell(series_detail(s))});
  }
  for (const v1::ImportedStructure& i : r.structures()) {
    const v1::Structure& s = i.structure();
    std::string detail = s.name();
    if (!s.laterality().empty()) detail += " " + s.laterality();
    detail += ", " + std::to_string(i.voxel_count()) + " voxels on series " + i.referenced_series_uid();
    if (i.replaced()) detail += " (re-import: updated)";
    out.row({text_cell("structure"), int_cell(s.id()), text_cell(s.patient_id()), text_cell(detail)});
  }
  out.end();
}

}  // namespace

void print_import_report(const v1::ImportDicomResponse& r, const std::string& format) {
  print_rows(r, format);
  std::fflush(stdout);  // the rows before the problems and the summary on a shared terminal
  for (const v1::ImportProblem& p : r.problems()) {
    std::fprintf(stderr, "problem: %s%s%s: %s\n", p.path().c_str(), p.path().empty() ? "" : ": ", p.code().c_str(),
                 p.message().c_str());
  }
  int updated = 0;
  for (const v1::ImportedStructure& i : r.structures()) updated += i.replaced() ? 1 : 0;
  const std::string reimported =
      updated == 0 ? "" : ", " + std::to_string(updated) + " of the structures were there already and were updated";
  std::fprintf(stderr, "imported %d series and %d structures from %lld files (%.1f MB) in %.1f s; %d problems%s\n",
               r.series_size(), r.structures_size(), (long long)r.files_received(), double(r.bytes_received()) / 1e6,
               r.milliseconds() / 1000.0, r.problems_size(), reimported.c_str());
}

}  // namespace soiq::cli
