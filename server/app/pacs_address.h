#pragma once
// The PACS soiqd talks to, as one flag value (soiqd --pacs, SOIQ_PACS): "AE@HOST:PORT", e.g.
// "ORTHANC@pacs.example.org:4242" or "SOIQTEST@127.0.0.1:11112".
//
// Inputs   text: AE title, '@', host, ':', port. The AE title may not contain '@'; the host is a
//          name or IPv4 address (the last ':' separates the port). calling_ae and
//          timeout_seconds go into the peer unchanged.
// Output   A PacsPeer that passed dicom::validate_pacs_peer.
// Errors   INVALID_ARGUMENT naming what is missing or wrong and the expected form.

#include <string>

#include "core/base/status.h"
#include "dicom/pacs_peer.h"

namespace soiq::server {

Result<dicom::PacsPeer> parse_pacs_address(const std::string& text, const std::string& calling_ae, int timeout_seconds);

}  // namespace soiq::server
