#include "dicom/pacs_pull.h"

#include <dcmtk/dcmnet/dimse.h>
#include <dcmtk/dcmnet/diutil.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>

#include "dicom/dcmtk_file.h"
#include "dicom/pacs_association.h"

namespace soiq::dicom {
namespace {

// The storage SOP classes we accept on the C-GET association. A study holding an instance of
// a class not listed here fails that sub-operation on the PACS side, and with it the pull, so
// the list is broad: everything a radiotherapy or radiology study commonly holds, not only what
// soiq imports. 1 C-GET model x2 + 33 classes stays well under the 128 contexts DICOM allows.
const char* const kStorageClasses[] = {
    UID_CTImageStorage,
    UID_EnhancedCTImageStorage,
    UID_LegacyConvertedEnhancedCTImageStorage,
    UID_MRImageStorage,
    UID_EnhancedMRImageStorage,
    UID_LegacyConvertedEnhancedMRImageStorage,
    UID_PositronEmissionTomographyImageStorage,
    UID_EnhancedPETImageStorage,
    UID_LegacyConvertedEnhancedPETImageStorage,
    UID_RTStructureSetStorage,
    UID_RTDoseStorage,
    UID_RTPlanStorage,
    UID_SegmentationStorage,
    UID_SpatialRegistrationStorage,
    UID_DeformableSpatialRegistrationStorage,
    UID_SecondaryCaptureImageStorage,
    UID_MultiframeGrayscaleByteSecondaryCaptureImageStorage,
    UID_MultiframeGrayscaleWordSecondaryCaptureImageStorage,
    UID_MultiframeTrueColorSecondaryCaptureImageStorage,
    UID_NuclearMedicineImageStorage,
    UID_ComputedRadiographyImageStorage,
    UID_DigitalXRayImageStorageForPresentation,
    UID_UltrasoundImageStorage,
    UID_UltrasoundMultiframeImageStorage,
    UID_XRayAngiographicImageStorage,
    UID_GrayscaleSoftcopyPresentationStateStorage,
    UID_BasicTextSRStorage,
    UID_EnhancedSRStorage,
    UID_ComprehensiveSRStorage,
    UID_KeyObjectSelectionDocumentStorage,
    UID_EncapsulatedPDFStorage,
    UID_RawDataStorage,
};

bool valid_uid(const std::string& uid) {
  return !uid.empty() && uid.size() <= 64 && std::all_of(uid.begin(), uid.end(), [](char c) {
    return c == '.' || std::isdigit(static_cast<unsigned char>(c));
  });
}

// "<uid>.dcm"; a UID is digits and dots, but the name comes from the network: anything else
// (a '/', "..") must not choose where the file goes.
std::string file_name_for(std::string sop_instance_uid) {
  for (char& c : sop_instance_uid)
    if (c != '.' && !std::isdigit(static_cast<unsigned char>(c))) c = '_';
  return sop_instance_uid + ".dcm";
}

// Receives the C-STORE sub-operations of one C-GET and writes each instance to dest_dir.
class GetScu : public DcmSCU {
 public:
  GetScu(std::filesystem::path dest_dir, const PacsPullCallback& progress)
      : dest_dir_(std::move(dest_dir)), progress_(progress) {}

  OFCondition handleCGETResponse(const T_ASC_PresentationContextID, RetrieveResponse* response,
                                 OFBool& continue_session) override {
    continue_session = OFFalse;
    if (response == nullptr) return DIMSE_NULLKEY;
    if (DICOM_PENDING_STATUS(response->m_status)) {
      remaining_ = response->m_numberOfRemainingSubops;
      continue_session = OFTrue;
      return EC_Normal;
    }
    final_ = Final{response->m_status, response->m_numberOfCompletedSubops, response->m_numberOfFailedSubops,
                   response->m_numberOfWarningSubops};
    return EC_Normal;
  }

  OFCondition handleSTORERequest(const T_ASC_PresentationContextID, DcmDataset* instance, OFBool& continue_session,
                                 Uint16& store_status) override {
    if (instance == nullptr) return DIMSE_NULLKEY;
    const std::string uid = get_string(*instance, DCM_SOPInstanceUID);
    if (uid.empty()) {
      // Refuse this one; the PACS counts it as failed and the pull fails with that count.
      delete instance;
      store_status = STATUS_STORE_Error_DataSetDoesNotMatchSOPClass;
      return EC_Normal;
    }
    const std::string path = (dest_dir_ / file_name_for(uid)).string();
    DcmFileFormat file(instance, OFFalse);  // takes ownership
    // EXS_Unknown keeps the transfer syntax the instance came in; a file meta header is added.
    const OFCondition cond = file.saveFile(path.c_str());
    if (cond.bad()) {
      std::remove(path.c_str());
      write_error_ = "cannot write '" + path + "' (" + cond.text() + ")";
      store_status = STATUS_STORE_Refused_OutOfResources;
      continue_session = OFFalse;
      return EC_Normal;
    }
    store_status = STATUS_Success;
    ++received_;
    paths_.insert(path);
    if (progress_ && !progress_(PacsPullProgress{received_, remaining_, path})) {
      cancelled_ = true;
      continue_session = OFFalse;
    }
    return EC_Normal;
  }

  struct Final {
    Uint16 status = 0;
    int completed = 0, failed = 0, warning = 0;
  };
  std::optional<Final> final_;
  int received_ = 0;
  int remaining_ = -1;
  std::set<std::string> paths_;
  std::string write_error_;
  bool cancelled_ = false;

 private:
  std::filesystem::path dest_dir_;
  const PacsPullCallback& progress_;
};

}  // namespace

Result<PacsPullResult> pacs_pull(const PacsPeer& peer, const std::string& study_uid, const std::string& dest_dir,
                                 const PacsPullCallback& progress) {
  SOIQ_RETURN_IF_ERROR(validate_pacs_peer(peer));
  if (!valid_uid(study_uid)) return invalid_argument("study_uid '" + study_uid + "' must be 1 to 64 digits and dots");
  std::error_code ec;
  std::filesystem::create_directories(dest_dir, ec);
  if (ec || !std::filesystem::is_directory(dest_dir))
    return invalid_argument("dest_dir '" + dest_dir + "' cannot be created" + (ec ? " (" + ec.message() + ")" : ""));

  const std::string what = "C-GET of study " + study_uid;
  GetScu scu(dest_dir, progress);
  configure_scu(scu, peer);
  scu.addPresentationContext(UID_GETStudyRootQueryRetrieveInformationModel, uncompressed_transfer_syntaxes());
  scu.addPresentationContext(UID_GETPatientRootQueryRetrieveInformationModel, uncompressed_transfer_syntaxes());
  // We are the SCP of the C-STORE sub-operations: role selection tells the PACS so (PS3.7 D.3.3.4).
  for (const char* sop_class : kStorageClasses)
    scu.addPresentationContext(sop_class, decodable_transfer_syntaxes(), ASC_SC_ROLE_SCP);
  SOIQ_RETURN_IF_ERROR(open_association(scu, peer, "C-GET"));

  // Study Root needs only the study uid at STUDY level; Patient Root is the fallback for a PACS
  // without it (most accept the study uid alone there too).
  T_ASC_PresentationContextID pcid =
      scu.findAnyPresentationContextID(UID_GETStudyRootQueryRetrieveInformationModel, "");
  if (pcid == 0) pcid = scu.findAnyPresentationContextID(UID_GETPatientRootQueryRetrieveInformationModel, "");
  if (pcid == 0) {
    close_association(scu, /*abort=*/true);
    return failed_precondition(describe_pacs_peer(peer) + " does not offer C-GET (Study or Patient Root) to us");
  }
  DcmDataset keys;
  keys.putAndInsertString(DCM_QueryRetrieveLevel, "STUDY");
  keys.putAndInsertString(DCM_StudyInstanceUID, study_uid.c_str());
  const OFCondition cond = scu.sendCGETRequest(pcid, &keys, nullptr);

  const std::string from = what + " from " + describe_pacs_peer(peer);
  if (scu.cancelled_) {
    close_association(scu, /*abort=*/true);
    return Status(StatusCode::kCancelled, from + " cancelled after " + std::to_string(scu.received_) + " instances");
  }
  if (!scu.write_error_.empty()) {
    close_association(scu, /*abort=*/true);
    return data_loss(from + ": " + scu.write_error_);
  }
  if (cond.bad()) {
    close_association(scu, /*abort=*/true);
    return association_failure(peer, what + " (after " + std::to_string(scu.received_) + " instances)", cond);
  }
  if (!scu.final_) {
    close_association(scu, /*abort=*/true);
    return Status(StatusCode::kUnavailable,
                  from + " ended without a final C-GET response after " + std::to_string(scu.received_) + " instances");
  }
  close_association(scu, /*abort=*/false);

  const auto& f = *scu.final_;
  const std::string counts = std::to_string(f.completed) + " completed, " + std::to_string(f.failed) + " failed, " +
                             std::to_string(f.warning) + " with warnings";
  if (f.failed > 0 ||
      (f.status != STATUS_Success && f.status != STATUS_GET_Warning_SubOperationsCompleteOneOrMoreFailures))
    return failed_precondition(from + " ended with status " + dimse_status_hex(f.status) + " (" +
                               DU_cgetStatusString(f.status) + "): " + counts +
                               "; failed sub-operations are usually instances of a SOP class or transfer syntax "
                               "soiq does not accept");
  if (f.completed + f.warning == 0 && scu.received_ == 0)
    return not_found("study " + study_uid + " has no instances on " + describe_pacs_peer(peer));
  if (scu.received_ != f.completed + f.warning)
    return data_loss(from + ": the PACS reports " + counts + " but " + std::to_string(scu.received_) +
                     " instances arrived");

  PacsPullResult result;
  result.completed = f.completed;
  result.failed = f.failed;
  result.warning = f.warning;
  result.paths.assign(scu.paths_.begin(), scu.paths_.end());
  return result;
}

}  // namespace soiq::dicom
