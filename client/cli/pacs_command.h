#pragma once
// `soiq pacs echo|find|pull|push`: the PACS soiqd was started with (soiqd --pacs AE@HOST:PORT),
// soiqd being the DICOM SCU.
//   echo                      C-ECHO; prints the PACS and the round trip
//   find [--level study|patient] [--patient ID] [--name NAME] [--study-date D|D1-D2|D1-|-D2]
//        [--modality CT[\PT]] [--study UID] [--accession A] [--max N] [--format table|json|csv]
//                             C-FIND; one row per match (wildcards * and ? in ID and NAME)
//   pull (--study UID... | --patient ID) [--format table|json|csv]
//                             C-GET into soiq, then the import (rows as `soiq import`); a progress
//                             bar of instances on a terminal; all or nothing; Ctrl-C cancels
//   push ID... [--description TEXT]
//                             the structures as one DICOM SEG, C-STOREd to the PACS
// Errors are one line with the exit code table's codes: 4 when soiqd has no PACS, 6 when the PACS
// cannot be reached, 7 when it refuses our AE title.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_pacs_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
