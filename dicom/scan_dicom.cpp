#include "dicom/scan_dicom.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "core/base/utf8.h"
#include "dicom/age_at_study.h"
#include "dicom/dcmtk_file.h"

namespace soiq::dicom {
namespace {

namespace fs = std::filesystem;

void fill_if_empty(std::string& field, const std::string& value) {
  if (field.empty()) field = value;
}

int64_t get_integer(DcmItem& item, const DcmTagKey& tag) {
  const auto v = get_number(item, tag);
  return v ? static_cast<int64_t>(*v) : 0;
}

// The Patient's Name in UTF-8 (load_dicom_file converted the character set); a name that could
// not be converted is left out rather than stored garbled.
std::string utf8_patient_name(DcmDataset& ds) {
  std::string name = get_string(ds, DCM_PatientName);
  return is_utf8(name) ? name : "";
}

// Accumulates records while files are read; turned into a DicomScan at the end.
class Index {
 public:
  explicit Index(DicomScan& scan) : scan_(scan) {}

  // Reads one path that exists: a folder, a DICOMDIR or an instance.
  void visit(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
      std::vector<fs::path> entries;
      for (const auto& e : fs::recursive_directory_iterator(
               path, fs::directory_options::follow_directory_symlink | fs::directory_options::skip_permission_denied,
               ec))
        if (e.is_regular_file(ec)) entries.push_back(e.path());
      std::sort(entries.begin(), entries.end());
      for (const auto& e : entries) visit_file(e);
      return;
    }
    visit_file(path);
  }

  void finish() {
    // Age at study: Patient's Age was taken per study while reading; otherwise the dates decide.
    for (auto& [uid, study] : studies_) {
      if (study.age_years) continue;
      const auto p = patients_.find(study.patient_id);
      if (p != patients_.end()) study.age_years = age_at_study("", p->second.birth_date, study.study_date);
    }
    for (auto& [id, p] : patients_) scan_.patients.push_back(p);
    for (auto& [uid, s] : studies_) scan_.studies.push_back(s);
    for (auto& [uid, s] : series_) {
      std::sort(s.instances.begin(), s.instances.end(), [](const DicomInstance& a, const DicomInstance& b) {
        return std::tie(a.instance_number, a.path) < std::tie(b.instance_number, b.path);
      });
      scan_.series.push_back(std::move(s));
    }
    std::sort(scan_.series.begin(), scan_.series.end(), [](const DicomSeries& a, const DicomSeries& b) {
      return std::tie(a.study_uid, a.series_number, a.series_uid) <
             std::tie(b.study_uid, b.series_number, b.series_uid);
    });
  }

 private:
  void visit_file(const fs::path& path) {
    std::error_code ec;
    const fs::path key = fs::weakly_canonical(path, ec);
    if (!seen_.insert(ec ? path.string() : key.string()).second) return;
    const std::string name = path.string();
    if (!looks_like_dicom(name)) {
      ++scan_.non_dicom_skipped;
      return;
    }
    auto file = load_dicom_file(name, /*until_pixel_data=*/true);
    if (!file.ok()) {
      scan_.unreadable.push_back({name, file.status()});
      return;
    }
    DcmDataset& ds = *(*file)->getDataset();
    if (ds.tagExists(DCM_DirectoryRecordSequence)) {
      visit_dicomdir(path, ds);
      return;
    }
    add_instance(name, ds);
  }

  void visit_dicomdir(const fs::path& path, DcmDataset& ds) {
    ++scan_.dicomdirs_read;
    const fs::path folder = path.parent_path();
    DcmItem* record = nullptr;
    for (long i = 0; ds.findAndGetSequenceItem(DCM_DirectoryRecordSequence, record, i).good(); ++i) {
      const std::string id = get_string_array(*record, DCM_ReferencedFileID);
      if (id.empty()) continue;  // PATIENT, STUDY and SERIES records reference no file
      fs::path file = folder;
      size_t start = 0;
      while (start <= id.size()) {
        const size_t end = std::min(id.find('\\', start), id.size());
        std::string part = id.substr(start, end - start);
        part.erase(part.find_last_not_of(' ') + 1);
        if (!part.empty()) file /= part;
        start = end + 1;
      }
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) {
        scan_.unreadable.push_back({file.string(), not_found("'" + file.string() + "': referenced by DICOMDIR '" +
                                                             path.string() + "' but missing")});
        continue;
      }
      visit_file(file);
    }
  }

  void add_instance(const std::string& path, DcmDataset& ds) {
    DicomInstance inst;
    inst.path = path;
    inst.sop_instance_uid = get_string(ds, DCM_SOPInstanceUID);
    inst.sop_class_uid = get_string(ds, DCM_SOPClassUID);
    inst.series_uid = get_string(ds, DCM_SeriesInstanceUID);
    inst.instance_number = get_integer(ds, DCM_InstanceNumber);
    Uint16 rows = 0, columns = 0;
    (void)ds.findAndGetUint16(DCM_Rows, rows);  // absent stays 0
    (void)ds.findAndGetUint16(DCM_Columns, columns);
    inst.rows = rows;
    inst.columns = columns;
    const std::string study_uid = get_string(ds, DCM_StudyInstanceUID);
    for (const auto& [value, tag] :
         {std::pair<const std::string*, const char*>{&inst.sop_instance_uid, "SOPInstanceUID (0008,0018)"},
          std::pair<const std::string*, const char*>{&inst.series_uid, "SeriesInstanceUID (0020,000E)"},
          std::pair<const std::string*, const char*>{&study_uid, "StudyInstanceUID (0020,000D)"}}) {
      if (value->empty()) {
        scan_.unreadable.push_back({path, invalid_argument("'" + path + "': DICOM file without " + std::string(tag))});
        return;
      }
    }
    ++scan_.files_read;

    const std::string patient_id = get_string(ds, DCM_PatientID);
    DicomPatient& p = patients_[patient_id];
    p.patient_id = patient_id;
    fill_if_empty(p.sex, get_string(ds, DCM_PatientSex));
    fill_if_empty(p.birth_date, get_string(ds, DCM_PatientBirthDate));
    if (p.name.empty()) p.name = utf8_patient_name(ds);

    DicomStudy& st = studies_[study_uid];
    st.study_uid = study_uid;
    fill_if_empty(st.patient_id, patient_id);
    fill_if_empty(st.study_date, get_string(ds, DCM_StudyDate));
    fill_if_empty(st.study_time, get_string(ds, DCM_StudyTime));
    fill_if_empty(st.description, get_string(ds, DCM_StudyDescription));
    fill_if_empty(st.accession_number, get_string(ds, DCM_AccessionNumber));
    fill_if_empty(st.study_id, get_string(ds, DCM_StudyID));
    if (!st.age_years) st.age_years = parse_patient_age(get_string(ds, DCM_PatientAge));

    DicomSeries& se = series_[inst.series_uid];
    se.series_uid = inst.series_uid;
    fill_if_empty(se.study_uid, study_uid);
    fill_if_empty(se.modality, get_string(ds, DCM_Modality));
    fill_if_empty(se.frame_of_reference_uid, get_string(ds, DCM_FrameOfReferenceUID));
    fill_if_empty(se.description, get_string(ds, DCM_SeriesDescription));
    if (se.series_number == 0) se.series_number = get_integer(ds, DCM_SeriesNumber);
    if (se.window_width <= 0) {
      const auto centre = get_number(ds, DCM_WindowCenter);
      const auto width = get_number(ds, DCM_WindowWidth);
      if (centre && width && std::isfinite(*centre) && std::isfinite(*width) && *width > 0) {
        se.window_center = *centre;
        se.window_width = *width;
      }
    }
    se.instances.push_back(std::move(inst));
  }

  DicomScan& scan_;
  std::set<std::string> seen_;
  std::map<std::string, DicomPatient> patients_;
  std::map<std::string, DicomStudy> studies_;
  std::map<std::string, DicomSeries> series_;
};

}  // namespace

Result<DicomScan> scan_dicom(const std::vector<std::string>& paths) {
  for (const auto& p : paths) {
    std::error_code ec;
    if (!fs::exists(p, ec)) return not_found("'" + p + "': no such file or folder");
  }
  DicomScan scan;
  Index index(scan);
  for (const auto& p : paths) index.visit(p);
  index.finish();
  return scan;
}

}  // namespace soiq::dicom
