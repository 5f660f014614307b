#pragma once
// dicom/'s one adapter to DCMTK's dcmnet (STYLE.md 3): a DcmSCU set up from a PacsPeer, an
// association opened with every failure turned into a precise Status, and DIMSE statuses in hex.
// Internal to dicom/ (pacs_echo/find/pull/store.cpp); the public headers never include DCMTK.
//
// Error codes, the same for every pacs_* call:
//   UNAVAILABLE          the PACS cannot be reached (refused, unresolved, connect timeout), the
//                        association broke, a message did not come within timeout_seconds, or
//                        the association was rejected transiently (busy, too many): retry later.
//   PERMISSION_DENIED    rejected with "calling AE title not recognized": register ours there.
//   FAILED_PRECONDITION  rejected for another permanent reason, e.g. "called AE title not
//                        recognized" (a wrong called_ae; dcmqrscp also says this when it does
//                        not list our calling AE), or no proposed presentation context accepted.
// Messages name the peer ("PACS 'X' at host:port") and keep DCMTK's text.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmnet/scu.h>

#include <string>

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::dicom {

// The transfer syntaxes proposed for queries, retrieves and received instances: Explicit VR
// Little Endian first, Implicit VR Little Endian (the one every SCP must support) second.
OFList<OFString> uncompressed_transfer_syntaxes();
// The uncompressed ones first, then every compressed syntax dicom/decompress_pixels.h decodes
// (JPEG baseline, extended and lossless; JPEG-LS lossless and near-lossless; RLE): what a C-GET
// accepts, so a PACS that stores compressed images need not (and often cannot) convert them.
OFList<OFString> decodable_transfer_syntaxes();

// Sets AE titles, address and timeouts (connect, ACSE, DIMSE in non-blocking mode, so no read
// waits forever). At the first call in the process it also silences dcmnet's logger (failures
// reach the caller as a Status) and sets TCP_NODELAY=1 in the environment unless already set
// (DCMTK's only switch for Nagle's algorithm, which made a C-GET 12x slower).
// Caveats: DCMTK's connect timeout is one process-wide setting; concurrent calls to peers with
// different timeout_seconds may use each other's value for the TCP connect only. The one-time
// setenv is not safe against a concurrent getenv in another thread; a server that cares sets
// TCP_NODELAY itself before starting threads.
void configure_scu(DcmSCU& scu, const PacsPeer& peer);

// initNetwork + negotiateAssociation with the errors above; `service` ("C-FIND") goes into them,
// `none_accepted_detail` (if any) into the message when no presentation context was accepted.
Status open_association(DcmSCU& scu, const PacsPeer& peer, const std::string& service,
                        const std::string& none_accepted_detail = "");

// A DCMTK failure on an open association (send, receive, timeout) as UNAVAILABLE naming the peer.
Status association_failure(const PacsPeer& peer, const std::string& what, const OFCondition& cond);

// "0xA700" style: the DIMSE status as the standard prints it.
std::string dimse_status_hex(Uint16 status);

// Releases the association if one is open (A-RELEASE, or A-ABORT when `abort`).
void close_association(DcmSCU& scu, bool abort);

}  // namespace soiq::dicom
