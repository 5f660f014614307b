#pragma once
// The PACS soiq talks to as a DICOM SCU (docs/DESIGN.md "DICOM and PACS"): who
// it is (called AE title), where it listens, who we are (calling AE title), and how long to wait.
// Every pacs_* call (pacs_echo.h, pacs_find.h, pacs_pull.h, pacs_store.h) validates its peer first.
//
// Inputs   called_ae, calling_ae: 1..16 characters of the DICOM AE repertoire (printable ASCII
//          except backslash), not all spaces. host: a name or IPv4 address, non-empty, no spaces.
//          port: 1..65535. timeout_seconds: 1..3600, used for the TCP connect, each association
//          message and each DIMSE message (so a stalled PACS stops a call after about that long,
//          however long the whole transfer is).
// Output   OK, or the first bad field.
// Errors   INVALID_ARGUMENT naming the field and the rule it breaks.
// Cost     O(field lengths); thread-safe.

#include <string>

#include "core/base/status.h"

namespace soiq::dicom {

struct PacsPeer {
  std::string called_ae;  // the PACS's AE title
  std::string host;
  int port = 0;
  std::string calling_ae = "SOIQ";  // ours; the PACS may only accept AE titles it knows
  int timeout_seconds = 30;
};

Status validate_pacs_peer(const PacsPeer& peer);

// "PACS 'ORTHANC' at 10.0.0.5:4242", the way every pacs_* message names its peer.
std::string describe_pacs_peer(const PacsPeer& peer);

}  // namespace soiq::dicom
