// The rows of `soiq pacs echo|find|pull|push` in the command table: the PACS soiqd was started with
// (soiqd --pacs AE@HOST:PORT). Each subcommand is a row of its own, run by run_pacs_command.
#include "client/cli/command_table.h"
#include "client/cli/pacs_command.h"

namespace soiq::cli {

std::vector<CommandSpec> pacs_commands() {
  const OptionSpec rows = {"--format", "table|json|csv", "table", "output format"};
  return {
      {"pacs echo",
       CommandGroup::kRemote,
       {"pacs echo"},
       "C-ECHO: is the PACS soiqd was started with reachable?",
       "Asks soiqd to send a DICOM C-ECHO to its PACS (soiqd --pacs AE@HOST:PORT).",
       {},
       {"soiq pacs echo"},
       run_pacs_command},
      {"pacs find",
       CommandGroup::kRemote,
       {"pacs find [--level study|patient] [--patient ID] [--name NAME] [--study-date D|D1-D2]",
        "          [--modality CT] [--study UID] [--accession A] [--max N] [--format ..]"},
       "C-FIND: the studies or patients of the PACS that match",
       "Asks the PACS (through soiqd) for the studies, or patients, that match every key given.",
       {{"--level", "study|patient", "study", "what to find"},
        {"--patient", "ID", "", "the patient id"},
        {"--name", "NAME", "", "the patient's name (DICOM wildcards * and ?)"},
        {"--study-date", "D|D1-D2", "", "a date or range, YYYYMMDD"},
        {"--modality", "M", "", "a modality in the study (CT, MR, PT)"},
        {"--study", "UID", "", "the study instance uid"},
        {"--accession", "A", "", "the accession number"},
        {"--max", "N", "the server's cap", "at most N matches"},
        rows},
       {"soiq pacs find --modality MR", "soiq pacs find --level patient --name 'DOE*'"},
       run_pacs_command},
      {"pacs pull",
       CommandGroup::kRemote,
       {"pacs pull (--study UID... | --patient ID) [--replace] [--format ..]"},
       "C-GET into soiq: imported like 'soiq import', all or nothing",
       "Asks soiqd to C-GET studies from the PACS and import them as 'soiq import' does, all or nothing.",
       {{"--study", "UID", "", "a study to pull; repeatable"},
        {"--patient", "ID", "", "every study of this patient"},
        {"--replace", "", "", "replace what soiqd stores under the same DICOM UIDs (as 'soiq import --replace')"},
        rows},
       {"soiq pacs pull --study 1.2.826.0.1.3680043.2.1125.1"},
       run_pacs_command},
      {"pacs push",
       CommandGroup::kRemote,
       {"pacs push ID... [--as seg|rtstruct] [--description TEXT]"},
       "a SEG or RT Structure Set of imported structures C-STOREd back to the PACS",
       "Exports imported structures as one DICOM SEG (as 'soiq export-seg') or one RT Structure Set (as 'soiq "
       "export-rtstruct') and C-STOREs it to the PACS.",
       {{"--as", "seg|rtstruct", "seg", "the object to store: a binary SEG or an RT Structure Set"},
        {"--description", "TEXT", "", "the series' description"}},
       {"soiq pacs push 1 2", "soiq pacs push --as rtstruct 1 2"},
       run_pacs_command},
  };
}

}  // namespace soiq::cli
