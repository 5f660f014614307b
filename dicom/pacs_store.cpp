#include "dicom/pacs_store.h"

#include <dcmtk/dcmnet/dimse.h>
#include <dcmtk/dcmnet/diutil.h>

#include <map>
#include <utility>

#include "dicom/dcmtk_file.h"
#include "dicom/pacs_association.h"

namespace soiq::dicom {
namespace {

// Presentation context IDs are the odd numbers 1..255; keep a margin below that limit of 128.
constexpr std::size_t kMaxContextsPerAssociation = 100;

struct FileToSend {
  std::string path;
  std::string sop_class;
  std::string transfer_syntax;
};

Result<FileToSend> read_header(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(auto file, load_dicom_file(path, /*until_pixel_data=*/true));
  FileToSend out{path, get_string(*file->getDataset(), DCM_SOPClassUID), ""};
  if (out.sop_class.empty() || get_string(*file->getDataset(), DCM_SOPInstanceUID).empty())
    return invalid_argument("'" + path + "' has no SOP Class UID or SOP Instance UID; it cannot be stored");
  // The transfer syntax the file is in: from its meta header, or as detected for a bare dataset.
  out.transfer_syntax = get_string(*file->getMetaInfo(), DCM_TransferSyntaxUID);
  if (out.transfer_syntax.empty()) out.transfer_syntax = DcmXfer(file->getDataset()->getOriginalXfer()).getXferID();
  return out;
}

Status refused_status(const PacsPeer& peer, const std::string& path, Uint16 status) {
  const std::string msg = describe_pacs_peer(peer) + " refused '" + path + "' with status " + dimse_status_hex(status) +
                          " (" + DU_cstoreStatusString(status) + ")";
  if ((status & 0xff00) == 0xa700) return resource_exhausted(msg);
  if ((status & 0xff00) == 0xa900 || (status & 0xf000) == 0xc000) return invalid_argument(msg);
  return failed_precondition(msg);
}

bool stored(Uint16 status) {
  // Success, or one of the C-STORE warnings (coercion 0xB000, elements discarded 0xB006,
  // data set does not match SOP class 0xB007): the instance is stored.
  return status == STATUS_Success || status == 0xB000 || status == 0xB006 || status == 0xB007;
}

Status store_batch(const PacsPeer& peer, const std::vector<FileToSend>& batch) {
  DcmSCU scu;
  configure_scu(scu, peer);
  std::map<std::pair<std::string, std::string>, bool> proposed;
  for (const FileToSend& f : batch) {
    if (!proposed.emplace(std::pair{f.sop_class, f.transfer_syntax}, true).second) continue;
    OFList<OFString> syntaxes;
    syntaxes.push_back(f.transfer_syntax.c_str());
    scu.addPresentationContext(f.sop_class.c_str(), syntaxes);
  }
  const FileToSend& first = batch.front();
  SOIQ_RETURN_IF_ERROR(open_association(scu, peer, "C-STORE",
                                        "none of the files can be stored, e.g. '" + first.path + "' (SOP class " +
                                            first.sop_class + ", transfer syntax " + first.transfer_syntax + ")"));
  for (const FileToSend& f : batch) {
    const T_ASC_PresentationContextID pcid =
        scu.findPresentationContextID(f.sop_class.c_str(), f.transfer_syntax.c_str());
    if (pcid == 0) {
      close_association(scu, /*abort=*/false);
      return failed_precondition(describe_pacs_peer(peer) + " does not accept '" + f.path + "': SOP class " +
                                 f.sop_class + " in transfer syntax " + f.transfer_syntax + " was not accepted");
    }
    Uint16 status = 0;
    const OFCondition cond = scu.sendSTORERequest(pcid, f.path.c_str(), nullptr, status);
    if (cond.bad()) {
      close_association(scu, /*abort=*/true);
      return association_failure(peer, "C-STORE of '" + f.path + "'", cond);
    }
    if (!stored(status)) {
      close_association(scu, /*abort=*/false);
      return refused_status(peer, f.path, status);
    }
  }
  close_association(scu, /*abort=*/false);
  return ok_status();
}

}  // namespace

Status pacs_store(const PacsPeer& peer, const std::vector<std::string>& files) {
  SOIQ_RETURN_IF_ERROR(validate_pacs_peer(peer));
  if (files.empty()) return invalid_argument("no files to store");
  // Read every header first, so a bad file stops the call before anything is sent.
  std::vector<FileToSend> all;
  for (const std::string& path : files) {
    SOIQ_ASSIGN_OR_RETURN(auto f, read_header(path));
    all.push_back(std::move(f));
  }
  std::vector<FileToSend> batch;
  std::map<std::pair<std::string, std::string>, bool> contexts;
  for (FileToSend& f : all) {
    contexts.emplace(std::pair{f.sop_class, f.transfer_syntax}, true);
    if (contexts.size() > kMaxContextsPerAssociation) {
      SOIQ_RETURN_IF_ERROR(store_batch(peer, batch));
      batch.clear();
      contexts.clear();
      contexts.emplace(std::pair{f.sop_class, f.transfer_syntax}, true);
    }
    batch.push_back(std::move(f));
  }
  return store_batch(peer, batch);
}

}  // namespace soiq::dicom
