#pragma once
// C-STORE of DICOM files to a PACS (docs/DESIGN.md "DICOM and PACS"), e.g. a
// converted volume pushed back as a DICOM SEG.
//
// Inputs   peer: see pacs_peer.h. files: DICOM files (Part 10 or bare datasets), each with a SOP
//          Class and SOP Instance UID. One presentation context is proposed per distinct (SOP
//          class, transfer syntax) pair of the files; each file is sent as stored, never
//          converted. More than 100 distinct pairs are sent over several associations.
// Output   OK when the PACS answered success or a warning (0xB000, 0xB006, 0xB007: stored,
//          possibly coerced) for every file, in order.
// Errors   INVALID_ARGUMENT for a bad peer or an empty list; NOT_FOUND / DATA_LOSS naming a file
//          that is missing or not readable DICOM (checked before any association); INVALID_ARGUMENT
//          naming a file without SOP Class or Instance UID. FAILED_PRECONDITION naming the file
//          when the PACS accepted no context for its SOP class and transfer syntax. On the first
//          refused file the call stops with its status in hex: RESOURCE_EXHAUSTED for 0xA7xx (out
//          of resources), INVALID_ARGUMENT for 0xA9xx / 0xCxxx (the PACS cannot use the data),
//          FAILED_PRECONDITION otherwise (e.g. 0x0122 SOP class not supported). Files before it
//          are stored; storing again is harmless (same SOP Instance UID). Connection and
//          association errors as in dicom/pacs_association.h.
// Cost     O(files) header reads, then one association per 100 context pairs; memory O(largest
//          file). Thread-safe.

#include <string>
#include <vector>

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::dicom {

Status pacs_store(const PacsPeer& peer, const std::vector<std::string>& files);

}  // namespace soiq::dicom
