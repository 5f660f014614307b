#include "dicom/pacs_association.h"

#include <dcmtk/dcmnet/assoc.h>
#include <dcmtk/dcmnet/diutil.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace soiq::dicom {
namespace {

void set_up_dcmnet_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    // DcmSCU logs every failed receive and rejected association at ERROR level to stderr; the
    // caller gets the same facts as a Status, and soiqd must not write to stderr per request.
    DCM_dcmnetLogger.setLogLevel(OFLogger::OFF_LOG_LEVEL);
    // Debian's DCMTK leaves Nagle's algorithm on unless TCP_NODELAY is set in the environment,
    // which DCMTK reads at each connect and offers no API for. With it on, every small DIMSE
    // response waits for a delayed ACK: a C-GET of 98 instances on loopback took 7.6 s instead
    // of 0.6 s. An existing value (TCP_NODELAY=0) is kept. Once, at the first PACS call.
    ::setenv("TCP_NODELAY", "1", /*overwrite=*/0);
  });
}

// DCMTK's multi-line texts on one line: "a\nb" -> "a; b".
std::string one_line(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n')
      out += "; ";
    else
      out += c;
  }
  return out;
}

// The A-ASSOCIATE-RJ reason in words, e.g. "rejected permanent by service user: called AE title
// not recognized". DcmSCU keeps the reject parameters private, so we ask again with a minimal
// association (Verification only, same AE titles) through the lower ASC API and read them there.
// Only on the error path; a second answer that differs (a PACS that was busy a moment ago) is
// reported as what it is.
struct RejectReason {
  bool known = false;
  bool transient = false;
  int source = 0;  // 1 service user, 2 ACSE provider, 3 presentation provider
  int reason = 0;
  std::string text;
};

RejectReason ask_reject_reason(const PacsPeer& peer) {
  RejectReason out;
  T_ASC_Network* net = nullptr;
  if (ASC_initializeNetwork(NET_REQUESTOR, 0, peer.timeout_seconds, &net).bad()) return out;
  T_ASC_Parameters* params = nullptr;
  T_ASC_Association* assoc = nullptr;
  if (ASC_createAssociationParameters(&params, ASC_DEFAULTMAXPDU).good()) {
    ASC_setAPTitles(params, peer.calling_ae.c_str(), peer.called_ae.c_str(), nullptr);
    const std::string address = peer.host + ":" + std::to_string(peer.port);
    ASC_setPresentationAddresses(params, OFStandard::getHostName().c_str(), address.c_str());
    const char* syntaxes[] = {UID_LittleEndianImplicitTransferSyntax};
    ASC_addPresentationContext(params, 1, UID_VerificationSOPClass, syntaxes, 1);
    const OFCondition cond = ASC_requestAssociation(net, params, &assoc);
    if (cond == DUL_ASSOCIATIONREJECTED) {
      T_ASC_RejectParameters rej;
      ASC_getRejectParameters(params, &rej);
      OFString text;
      ASC_printRejectParameters(text, &rej);
      out.known = true;
      out.transient = rej.result == ASC_RESULT_REJECTEDTRANSIENT;
      out.source = static_cast<int>(rej.source) & 0xff;
      out.reason = static_cast<int>(rej.reason) & 0xff;
      // DCMTK prints "Result: Rejected Permanent, Source: Service User\nReason: ..." on two lines.
      out.text = one_line(text.c_str());
    } else if (cond.good()) {
      ASC_abortAssociation(assoc);
    }
    // ASC_destroyAssociation frees the parameters it was given; without one they are ours.
    if (assoc != nullptr)
      ASC_destroyAssociation(&assoc);
    else
      ASC_destroyAssociationParameters(&params);
  }
  ASC_dropNetwork(&net);
  return out;
}

Status rejected_status(const PacsPeer& peer, const std::string& service) {
  const std::string who = describe_pacs_peer(peer);
  const RejectReason why = ask_reject_reason(peer);
  const std::string head = who + " rejected the " + service + " association (calling AE '" + peer.calling_ae + "')";
  if (!why.known) return failed_precondition(head + "; the reason could not be read back");
  const std::string msg = head + ": " + why.text;
  if (why.transient) return Status(StatusCode::kUnavailable, msg + "; retry later");
  // PS3.8 9.3.4: service-user reason 3 is "calling AE title not recognized", 7 "called AE title
  // not recognized".
  if (why.source == 1 && why.reason == 3)
    return Status(StatusCode::kPermissionDenied, msg + "; ask the PACS administrator to register our AE title");
  // Reason 7 is "called AE title not recognized", but some PACS (dcmqrscp among them) give it for an
  // unknown calling AE too: either way the PACS refuses this pair of AE titles, which is a matter
  // of its configuration (permission), not of the request.
  if (why.source == 1 && why.reason == 7)
    return Status(StatusCode::kPermissionDenied, msg + "; check the PACS's AE title ('" + peer.called_ae +
                                                     "') and that the PACS lists ours ('" + peer.calling_ae +
                                                     "'): some PACS, dcmqrscp among them, give this reason for both");
  return failed_precondition(msg);
}

}  // namespace

OFList<OFString> uncompressed_transfer_syntaxes() {
  OFList<OFString> out;
  out.push_back(UID_LittleEndianExplicitTransferSyntax);
  out.push_back(UID_LittleEndianImplicitTransferSyntax);
  return out;
}

OFList<OFString> decodable_transfer_syntaxes() {
  OFList<OFString> out = uncompressed_transfer_syntaxes();
  for (const char* uid :
       {UID_JPEGProcess14SV1TransferSyntax, UID_JPEGProcess14TransferSyntax, UID_JPEGLSLosslessTransferSyntax,
        UID_RLELosslessTransferSyntax, UID_JPEGProcess1TransferSyntax, UID_JPEGProcess2_4TransferSyntax,
        UID_JPEGLSLossyTransferSyntax})
    out.push_back(uid);
  return out;
}

void configure_scu(DcmSCU& scu, const PacsPeer& peer) {
  set_up_dcmnet_once();
  scu.setAETitle(peer.calling_ae.c_str());
  scu.setPeerAETitle(peer.called_ae.c_str());
  scu.setPeerHostName(peer.host.c_str());
  scu.setPeerPort(static_cast<Uint16>(peer.port));
  scu.setConnectionTimeout(peer.timeout_seconds);
  scu.setACSETimeout(static_cast<Uint32>(peer.timeout_seconds));
  scu.setDIMSEBlockingMode(DIMSE_NONBLOCKING);
  scu.setDIMSETimeout(static_cast<Uint32>(peer.timeout_seconds));
  scu.setVerbosePCMode(OFFalse);
  scu.setProgressNotificationMode(OFFalse);
}

Status open_association(DcmSCU& scu, const PacsPeer& peer, const std::string& service,
                        const std::string& none_accepted_detail) {
  OFCondition cond = scu.initNetwork();
  if (cond.bad())
    return internal_error("cannot set up the network for " + service + " with " + describe_pacs_peer(peer) + " (" +
                          cond.text() + ")");
  cond = scu.negotiateAssociation();
  if (cond.good()) return ok_status();
  if (cond == DUL_ASSOCIATIONREJECTED) return rejected_status(peer, service);
  if (cond == NET_EC_NoAcceptablePresentationContexts)
    return failed_precondition(
        describe_pacs_peer(peer) + " accepted none of the presentation contexts proposed for " + service +
        (none_accepted_detail.empty() ? "; it does not offer this service to us" : ": " + none_accepted_detail));
  // Refused, unresolvable host, connect or ACSE timeout: DCMTK's text says which
  // ("TCP Initialization Error: Connection refused", "Attempt to connect to unknown host").
  return Status(StatusCode::kUnavailable,
                "cannot reach " + describe_pacs_peer(peer) + " for " + service + ": " + one_line(cond.text()));
}

Status association_failure(const PacsPeer& peer, const std::string& what, const OFCondition& cond) {
  std::string reason = cond.text();
  if (cond == DIMSE_NODATAAVAILABLE)
    reason = "no answer within " + std::to_string(peer.timeout_seconds) + " s (" + reason + ")";
  return Status(StatusCode::kUnavailable, what + " with " + describe_pacs_peer(peer) + " failed: " + reason);
}

std::string dimse_status_hex(Uint16 status) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04X", static_cast<unsigned>(status));
  return buf;
}

void close_association(DcmSCU& scu, bool abort) {
  if (!scu.isConnected()) return;
  if (abort)
    scu.abortAssociation();
  else
    scu.releaseAssociation();
}

}  // namespace soiq::dicom
