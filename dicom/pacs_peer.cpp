#include "dicom/pacs_peer.h"

#include <algorithm>

namespace soiq::dicom {
namespace {

constexpr int kMaxTimeoutSeconds = 3600;

Status validate_ae_title(const std::string& field, const std::string& ae) {
  if (ae.empty() || ae.size() > 16)
    return invalid_argument(field + " '" + ae + "' must have 1 to 16 characters (it has " + std::to_string(ae.size()) +
                            ")");
  // PS3.5 6.2: AE is the default repertoire without backslash and control characters; leading
  // and trailing spaces are padding, so an all-space title is empty.
  for (const char c : ae) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u > 0x7e || c == '\\')
      return invalid_argument(field + " '" + ae + "' may only contain printable ASCII characters other than backslash");
  }
  if (std::all_of(ae.begin(), ae.end(), [](char c) { return c == ' '; }))
    return invalid_argument(field + " must not be all spaces");
  return ok_status();
}

}  // namespace

Status validate_pacs_peer(const PacsPeer& peer) {
  SOIQ_RETURN_IF_ERROR(validate_ae_title("called_ae", peer.called_ae));
  SOIQ_RETURN_IF_ERROR(validate_ae_title("calling_ae", peer.calling_ae));
  if (peer.host.empty()) return invalid_argument("host must not be empty");
  for (const char c : peer.host) {
    const auto u = static_cast<unsigned char>(c);
    if (u <= 0x20 || u > 0x7e)
      return invalid_argument("host '" + peer.host + "' may not contain spaces, control or non-ASCII characters");
  }
  if (peer.port < 1 || peer.port > 65535)
    return invalid_argument("port " + std::to_string(peer.port) + " is outside 1..65535");
  if (peer.timeout_seconds < 1 || peer.timeout_seconds > kMaxTimeoutSeconds)
    return invalid_argument("timeout_seconds " + std::to_string(peer.timeout_seconds) + " is outside 1.." +
                            std::to_string(kMaxTimeoutSeconds));
  return ok_status();
}

std::string describe_pacs_peer(const PacsPeer& peer) {
  return "PACS '" + peer.called_ae + "' at " + peer.host + ":" + std::to_string(peer.port);
}

}  // namespace soiq::dicom
