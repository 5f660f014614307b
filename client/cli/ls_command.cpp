#include "client/cli/ls_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/record_args.h"
#include "client/cli/remote_options.h"
#include "client/cli/row_printer.h"
#include "client/cli/show_records.h"

namespace soiq::cli {

namespace {

struct LsArgs {
  std::string what = "patients";
  std::string patient, study, name, laterality, sex;
  std::string format = "table";
  bool all = false;
  int page_size = 100;
};

Result<LsArgs> parse_ls_args(int argc, char** argv) {
  LsArgs a;
  bool what_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--all") {
      a.all = true;
      continue;
    }
    if (arg.size() > 1 && arg[0] == '-') {
      if (arg != "--patient" && arg != "--study" && arg != "--name" && arg != "--laterality" && arg != "--sex" &&
          arg != "--format" && arg != "--page-size") {
        return invalid_argument("unknown option '" + arg + "'");
      }
      SOIQ_ASSIGN_OR_RETURN(const std::string v, option_value(argc, argv, i));
      if (arg == "--patient") a.patient = v;
      if (arg == "--study") a.study = v;
      if (arg == "--name") a.name = v;
      if (arg == "--laterality") {
        SOIQ_RETURN_IF_ERROR(in_option(check_laterality(v), arg));
        a.laterality = v;
      }
      if (arg == "--sex") {
        SOIQ_RETURN_IF_ERROR(in_option(check_sex(v), arg));
        a.sex = v;
      }
      if (arg == "--format") {
        SOIQ_RETURN_IF_ERROR(check_row_format(v));
        a.format = v;
      }
      if (arg == "--page-size") {
        SOIQ_ASSIGN_OR_RETURN(a.page_size, parse_int(v, "--page-size", 1, 1000));
      }
    } else if (!what_given && (arg == "patients" || arg == "studies" || arg == "structures")) {
      a.what = arg;
      what_given = true;
    } else {
      return invalid_argument("unexpected argument '" + arg + "' (patients, studies or structures)");
    }
  }
  auto only_for = [&](const std::string& value, const char* flag, const char* which) -> Status {
    if (value.empty() || a.what == which) return ok_status();
    return invalid_argument(std::string(flag) + " filters " + which + ", not " + a.what);
  };
  SOIQ_RETURN_IF_ERROR(only_for(a.sex, "--sex", "patients"));
  SOIQ_RETURN_IF_ERROR(only_for(a.study, "--study", "structures"));
  SOIQ_RETURN_IF_ERROR(only_for(a.name, "--name", "structures"));
  SOIQ_RETURN_IF_ERROR(only_for(a.laterality, "--laterality", "structures"));
  return a;
}

// Lists page after page while `all`; `fetch(token)` returns the next token after printing a page.
template <typename Fetch>
Status pages(const LsArgs& a, Fetch fetch) {
  std::string token;
  do {
    SOIQ_ASSIGN_OR_RETURN(token, fetch(token));
  } while (a.all && !token.empty());
  if (!token.empty())
    std::fprintf(stderr, "soiq ls: more %s on the server; pass --all to list them all\n", a.what.c_str());
  return ok_status();
}

Status ls(const LsArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  if (a.what == "patients") {
    RowPrinter out(a.format, patient_columns());
    SOIQ_RETURN_IF_ERROR(pages(a, [&](const std::string& token) -> Result<std::string> {
      soiq::v1::ListPatientsRequest r;
      r.set_patient_id_glob(a.patient);
      r.set_sex(a.sex);
      r.set_page_size(a.page_size);
      r.set_page_token(token);
      SOIQ_ASSIGN_OR_RETURN(const soiq::v1::ListPatientsResponse page, c.list_patients(r));
      for (const auto& p : page.patients()) out.row(patient_cells(p));
      return page.next_page_token();
    }));
    out.end();
  } else if (a.what == "studies") {
    RowPrinter out(a.format, study_columns());
    SOIQ_RETURN_IF_ERROR(pages(a, [&](const std::string& token) -> Result<std::string> {
      soiq::v1::ListStudiesRequest r;
      r.set_patient_id(a.patient);
      r.set_page_size(a.page_size);
      r.set_page_token(token);
      SOIQ_ASSIGN_OR_RETURN(const soiq::v1::ListStudiesResponse page, c.list_studies(r));
      for (const auto& s : page.studies()) out.row(study_cells(s));
      return page.next_page_token();
    }));
    out.end();
  } else {
    RowPrinter out(a.format, structure_columns());
    SOIQ_RETURN_IF_ERROR(pages(a, [&](const std::string& token) -> Result<std::string> {
      soiq::v1::ListStructuresRequest r;
      r.set_patient_id(a.patient);
      r.set_study_uid(a.study);
      r.set_name_glob(a.name);
      r.set_laterality(a.laterality);
      r.set_page_size(a.page_size);
      r.set_page_token(token);
      SOIQ_ASSIGN_OR_RETURN(const soiq::v1::ListStructuresResponse page, c.list_structures(r));
      for (const auto& s : page.structures()) out.row(structure_cells(s));
      return page.next_page_token();
    }));
    out.end();
  }
  return ok_status();
}

}  // namespace

int run_ls_command(int argc, char** argv, const client::ClientOptions& remote) {
  return run_command("ls", parse_ls_args(argc, argv), [&](const LsArgs& a) { return ls(a, remote); });
}

}  // namespace soiq::cli
