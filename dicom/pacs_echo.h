#pragma once
// C-ECHO: is the PACS there and does it talk to us (docs/DESIGN.md "DICOM and PACS").
// Opens an association proposing only the Verification SOP class.
//
// Inputs   peer: validated by validate_pacs_peer (pacs_peer.h).
// Output   OK when the association was accepted and the C-ECHO answered.
// Errors   INVALID_ARGUMENT for a bad peer field; UNAVAILABLE, PERMISSION_DENIED,
//          FAILED_PRECONDITION as listed in dicom/pacs_association.h (not reachable, rejected
//          with the A-ASSOCIATE-RJ reason, Verification not accepted).
// Cost     one association; at most about 3 x timeout_seconds when the PACS stalls. Thread-safe
//          (one DcmSCU per call).

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::dicom {

Status pacs_echo(const PacsPeer& peer);

}  // namespace soiq::dicom
