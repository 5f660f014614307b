#include "server/app/pacs_address.h"

#include <charconv>

namespace soiq::server {

Result<dicom::PacsPeer> parse_pacs_address(const std::string& text, const std::string& calling_ae,
                                           int timeout_seconds) {
  const std::string form = " (expected AE@HOST:PORT, e.g. ORTHANC@127.0.0.1:4242)";
  const size_t at = text.find('@');
  const size_t colon = text.rfind(':');
  if (at == std::string::npos || at == 0) return invalid_argument("PACS '" + text + "' has no AE title" + form);
  if (colon == std::string::npos || colon < at) return invalid_argument("PACS '" + text + "' has no port" + form);
  dicom::PacsPeer peer;
  peer.called_ae = text.substr(0, at);
  peer.host = text.substr(at + 1, colon - at - 1);
  const std::string port = text.substr(colon + 1);
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), peer.port);
  if (port.empty() || ec != std::errc() || end != port.data() + port.size())
    return invalid_argument("PACS '" + text + "' has port '" + port + "', not a number" + form);
  peer.calling_ae = calling_ae;
  peer.timeout_seconds = timeout_seconds;
  const Status valid = dicom::validate_pacs_peer(peer);
  if (!valid.ok()) return invalid_argument("PACS '" + text + "': " + valid.message() + form);
  return peer;
}

}  // namespace soiq::server
