#pragma once
// soiq's PACS client (docs/DESIGN.md "DICOM and PACS"): soiq as a DICOM SCU.
// One header per operation, each with its contract; this one gathers them for callers that use
// several. DCMTK's dcmnet stays inside dicom/ (pacs_association.cpp is the adapter).
//
//   pacs_peer.h   PacsPeer, validate_pacs_peer: who the PACS is and how long to wait for it.
//   pacs_echo.h   pacs_echo: C-ECHO.
//   pacs_find.h   pacs_find: C-FIND at PATIENT or STUDY level, Patient or Study Root.
//   pacs_pull.h   pacs_pull: C-GET of a study into a folder, complete or an error.
//   pacs_store.h  pacs_store: C-STORE of files.
//
// Error codes shared by all (dicom/pacs_association.h): UNAVAILABLE not reachable, broken or
// stalled; PERMISSION_DENIED the PACS does not know our AE title; FAILED_PRECONDITION rejected
// otherwise or service not offered; DIMSE failures carry the status in hex.

#include "dicom/pacs_echo.h"
#include "dicom/pacs_find.h"
#include "dicom/pacs_peer.h"
#include "dicom/pacs_pull.h"
#include "dicom/pacs_store.h"
