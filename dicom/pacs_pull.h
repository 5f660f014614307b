#pragma once
// C-GET of one study into a folder (docs/DESIGN.md "DICOM and PACS"): the PACS
// sends each instance back as a C-STORE on our own association, so no C-MOVE destination has to
// be configured on the PACS. The server imports the folder only when the pull is complete.
//
// Inputs   peer: see pacs_peer.h. study_uid: digits and dots, 1..64 characters.
//          dest_dir: created if missing; each instance is written there as a Part 10 file named
//          after its SOP Instance UID ("<uid>.dcm", anything but digits and dots replaced by '_'),
//          in the transfer syntax it came in. progress: optional, called after each written
//          instance; returning false cancels the pull.
//          Accepted instances: CT, MR, PET (also Enhanced and Legacy Converted Enhanced), RT
//          Structure Set, Dose and Plan, Segmentation, Spatial Registration, Secondary Capture,
//          NM, CR, DX, US, XA, presentation states, SR, Key Objects and encapsulated PDF, in
//          Explicit or Implicit VR Little Endian or a compressed syntax the import decodes
//          (decodable_transfer_syntaxes in dicom/pacs_association.h); others the PACS must
//          convert, or the sub-operation fails.
// Output   PacsPullResult: the PACS's final sub-operation counts and the paths written, sorted.
// Errors   INVALID_ARGUMENT for a bad peer, study_uid or a dest_dir that cannot be created.
//          NOT_FOUND when the PACS completes the C-GET with no instance ("study X has no
//          instances on PACS Y"). FAILED_PRECONDITION when the PACS reports failed
//          sub-operations (typically instances of a SOP class or transfer syntax we do not
//          accept) or a final status other than success (status in hex). UNAVAILABLE when the
//          association breaks or stalls midway. CANCELLED when progress returned false.
//          DATA_LOSS when an instance cannot be written (disk full) or the PACS's counts
//          disagree with the instances received. Connection and association errors as in dicom/pacs_association.h.
//          On any error dest_dir may hold some instances: discard it, nothing is half-imported.
// Cost     one association; memory O(largest instance). Thread-safe for distinct dest_dirs.

#include <functional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::dicom {

struct PacsPullProgress {
  int received = 0;    // instances written so far
  int remaining = -1;  // from the PACS's last pending C-GET response; -1 before the first
  std::string path;    // the file just written
};

// Return false to cancel the pull.
using PacsPullCallback = std::function<bool(const PacsPullProgress&)>;

struct PacsPullResult {
  int completed = 0;  // sub-operations, as the PACS counts them
  int failed = 0;
  int warning = 0;
  std::vector<std::string> paths;  // files written, sorted
};

Result<PacsPullResult> pacs_pull(const PacsPeer& peer, const std::string& study_uid, const std::string& dest_dir,
                                 const PacsPullCallback& progress = {});

}  // namespace soiq::dicom
