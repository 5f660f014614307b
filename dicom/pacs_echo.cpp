#include "dicom/pacs_echo.h"

#include "dicom/pacs_association.h"

namespace soiq::dicom {

Status pacs_echo(const PacsPeer& peer) {
  SOIQ_RETURN_IF_ERROR(validate_pacs_peer(peer));
  DcmSCU scu;
  configure_scu(scu, peer);
  scu.addPresentationContext(UID_VerificationSOPClass, uncompressed_transfer_syntaxes());
  SOIQ_RETURN_IF_ERROR(open_association(scu, peer, "C-ECHO"));
  const OFCondition cond = scu.sendECHORequest(0);
  if (cond.bad()) {
    close_association(scu, /*abort=*/true);
    return association_failure(peer, "C-ECHO", cond);
  }
  close_association(scu, /*abort=*/false);
  return ok_status();
}

}  // namespace soiq::dicom
