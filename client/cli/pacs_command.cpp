#include "client/cli/pacs_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/import_report.h"
#include "client/cli/progress_bar.h"
#include "client/cli/quiet.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "client/cli/row_printer.h"

namespace soiq::cli {
namespace {

namespace v1 = soiq::v1;

struct PacsArgs {
  std::string verb;  // echo, find, pull, push
  std::string format = "table";
  v1::PacsFindRequest find;
  v1::PacsPullRequest pull;
  v1::PacsPushRequest push;
};

Status parse_find_option(int argc, char** argv, int& i, v1::PacsFindRequest& f) {
  const std::string arg = argv[i];
  SOIQ_ASSIGN_OR_RETURN(const std::string v, option_value(argc, argv, i));
  if (arg == "--level") {
    if (v != "study" && v != "patient") return invalid_argument("--level must be study or patient, got '" + v + "'");
    f.set_level(v == "patient" ? v1::PACS_LEVEL_PATIENT : v1::PACS_LEVEL_STUDY);
  } else if (arg == "--patient") {
    f.set_patient_id(v);
  } else if (arg == "--name") {
    f.set_patient_name(v);
  } else if (arg == "--study-date") {
    f.set_study_date(v);
  } else if (arg == "--modality") {
    f.set_modalities(v);
  } else if (arg == "--study") {
    f.set_study_uid(v);
  } else if (arg == "--accession") {
    f.set_accession_number(v);
  } else {  // --max
    SOIQ_ASSIGN_OR_RETURN(const int n, parse_int(v, "--max", 1, 10000));
    f.set_max_matches(n);
  }
  return ok_status();
}

Result<PacsArgs> parse_pacs_args(int argc, char** argv) {
  PacsArgs a;
  if (argc < 2) return invalid_argument("missing what to do: echo, find, pull or push");
  a.verb = argv[1];
  if (a.verb != "echo" && a.verb != "find" && a.verb != "pull" && a.verb != "push")
    return invalid_argument("unknown pacs command '" + a.verb + "' (echo, find, pull, push)");
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool find_key = arg == "--level" || arg == "--patient" || arg == "--name" || arg == "--study-date" ||
                          arg == "--modality" || arg == "--study" || arg == "--accession" || arg == "--max";
    if (arg == "--format" && (a.verb == "find" || a.verb == "pull")) {
      SOIQ_ASSIGN_OR_RETURN(a.format, option_value(argc, argv, i));
      SOIQ_RETURN_IF_ERROR(check_row_format(a.format));
    } else if (a.verb == "find" && find_key) {
      SOIQ_RETURN_IF_ERROR(parse_find_option(argc, argv, i, a.find));
    } else if (a.verb == "pull" && arg == "--study") {
      SOIQ_ASSIGN_OR_RETURN(*a.pull.add_study_uids(), option_value(argc, argv, i));
    } else if (a.verb == "pull" && arg == "--replace") {
      a.pull.set_replace(true);
    } else if (a.verb == "pull" && arg == "--patient") {
      SOIQ_ASSIGN_OR_RETURN(*a.pull.mutable_patient_id(), option_value(argc, argv, i));
    } else if (a.verb == "push" && arg == "--as") {
      SOIQ_ASSIGN_OR_RETURN(const std::string object, option_value(argc, argv, i));
      if (object != "seg" && object != "rtstruct")
        return invalid_argument("--as takes seg or rtstruct, not '" + object + "'");
      a.push.set_object(object == "rtstruct" ? v1::PUSHED_OBJECT_RTSTRUCT : v1::PUSHED_OBJECT_SEG);
    } else if (a.verb == "push" && arg == "--description") {
      SOIQ_ASSIGN_OR_RETURN(*a.push.mutable_series_description(), option_value(argc, argv, i));
    } else if (a.verb == "push" && !(arg.size() > 1 && arg[0] == '-')) {
      SOIQ_ASSIGN_OR_RETURN(const int64_t id, parse_structure_id(arg));
      a.push.add_structure_ids(id);
    } else {
      return invalid_argument("unexpected argument '" + arg + "' for 'soiq pacs " + a.verb + "'");
    }
  }
  if (a.verb == "pull" && a.pull.study_uids().empty() == a.pull.patient_id().empty())
    return invalid_argument("pull needs --study UID (one or more) or --patient ID, not both");
  if (a.verb == "push" && a.push.structure_ids().empty()) return invalid_argument("push needs structure ids");
  return a;
}

void print_matches(const v1::PacsFindResponse& r, const std::string& format, bool patient_level) {
  if (patient_level) {
    RowPrinter out(format, {"patient_id", "patient_name", "sex", "birth_date"});
    for (const v1::PacsMatch& m : r.matches())
      out.row({text_cell(m.patient_id()), text_cell(m.patient_name()), text_cell(m.patient_sex()),
               text_cell(m.patient_birth_date())});
    out.end();
    return;
  }
  RowPrinter out(format, {"patient_id", "patient_name", "sex", "birth_date", "study_uid", "study_date", "modalities",
                          "accession", "instances", "description"});
  for (const v1::PacsMatch& m : r.matches()) {
    out.row({text_cell(m.patient_id()), text_cell(m.patient_name()), text_cell(m.patient_sex()),
             text_cell(m.patient_birth_date()), text_cell(m.study_uid()), text_cell(m.study_date()),
             text_cell(m.modalities()), text_cell(m.accession_number()),
             m.number_of_instances() < 0 ? text_cell("") : int_cell(m.number_of_instances()),
             text_cell(m.study_description())});
  }
  out.end();
}

Status pull(const client::Client& c, const PacsArgs& a) {
  ProgressBar bar;
  auto r = c.pacs_pull(a.pull, [&](const v1::PacsPullProgress& p) {
    const std::string stage = "study " + std::to_string(p.study()) + "/" + std::to_string(p.studies());
    bar.update(stage, p.received(), p.remaining() < 0 ? 0 : p.received() + p.remaining());
    return true;
  });
  bar.clear();
  if (!r.ok() && interrupted()) return interrupted_by_user("nothing was imported");
  if (!r.ok()) return r.status();
  print_import_report(*r, a.format);
  return ok_status();
}

Status pacs(const PacsArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  if (a.verb == "echo") {
    SOIQ_ASSIGN_OR_RETURN(const v1::PacsEchoResponse r, c.pacs_echo());
    std::printf("%s answered C-ECHO in %.1f ms\n", r.pacs().c_str(), r.milliseconds());
    return ok_status();
  }
  if (a.verb == "find") {
    SOIQ_ASSIGN_OR_RETURN(const v1::PacsFindResponse r, c.pacs_find(a.find));
    print_matches(r, a.format, a.find.level() == v1::PACS_LEVEL_PATIENT);
    std::fflush(stdout);  // the rows before the summary line on a shared terminal
    if (!quiet())
      std::fprintf(stderr, "%d match%s on %s\n", r.matches_size(), r.matches_size() == 1 ? "" : "es", r.pacs().c_str());
    return ok_status();
  }
  if (a.verb == "pull") return pull(c, a);
  const Result<v1::PacsPushResponse> pushed = c.pacs_push(a.push);
  if (!pushed.ok() && interrupted())
    return interrupted_by_user("the PACS may have stored the object already ('soiq pacs find' shows its series)");
  SOIQ_ASSIGN_OR_RETURN(const v1::PacsPushResponse r, pushed);
  if (r.has_rt_struct()) {
    const v1::RtStructInfo& i = r.rt_struct();
    std::printf(
        "stored DICOM RT Structure Set %s (%d ROI%s, %lld contours, %lld bytes, on series %s) on %s in %.1f ms\n",
        i.sop_instance_uid().c_str(), i.rois(), i.rois() == 1 ? "" : "s", (long long)i.contours(),
        (long long)i.size_bytes(), i.referenced_series_uid().c_str(), r.pacs().c_str(), r.milliseconds());
    return ok_status();
  }
  std::printf("stored DICOM SEG %s (%d segment%s, %lld frames, %lld bytes, on series %s) on %s in %.1f ms\n",
              r.seg().sop_instance_uid().c_str(), r.seg().segments(), r.seg().segments() == 1 ? "" : "s",
              (long long)r.seg().frames(), (long long)r.seg().size_bytes(), r.seg().referenced_series_uid().c_str(),
              r.pacs().c_str(), r.milliseconds());
  return ok_status();
}

}  // namespace

int run_pacs_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_long_command("pacs", parse_pacs_args(argc, argv), remote,
                          [](const PacsArgs& a, const client::ClientOptions& options) { return pacs(a, options); });
}

}  // namespace soiq::cli
