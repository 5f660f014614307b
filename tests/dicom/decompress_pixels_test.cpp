// Compressed image files are read with exactly the pixel values of the uncompressed original: the
// test compresses CT_small.dcm itself with DCMTK's lossless encoders (JPEG Lossless SV1, JPEG-LS
// lossless, RLE), reads each as an image series and compares voxel for voxel. A transfer syntax
// without a decoder (JPEG 2000) and a corrupt stream are refused with the file named.

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcrleerg.h>
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmjpeg/djencode.h>
#include <dcmtk/dcmjpeg/djrplol.h>
#include <dcmtk/dcmjpls/djencode.h>
#include <dcmtk/dcmjpls/djrparam.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>

#include "dicom/read_image_series.h"
#include "dicom/scan_dicom.h"
#include "dicom_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
using testing::TempDir;

void register_encoders() {
  static std::once_flag once;
  std::call_once(once, [] {
    DJEncoderRegistration::registerCodecs();
    DJLSEncoderRegistration::registerCodecs();
    DcmRLEEncoderRegistration::registerCodecs();
  });
}

Result<SeriesImage> read_ct(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(const DicomScan scan, scan_dicom({path}));
  for (const DicomSeries& s : scan.series)
    if (s.modality == "CT") return read_image_series(s);
  return not_found("no CT series in " + path);
}

// CT_small.dcm re-encoded in `xfer` (losslessly), written to `out`.
void write_compressed(E_TransferSyntax xfer, const DcmRepresentationParameter* param, const std::string& out) {
  register_encoders();
  DcmFileFormat f;
  ASSERT_TRUE(f.loadFile(data_dir("dicom/CT_small.dcm").c_str()).good());
  ASSERT_TRUE(f.getDataset()->chooseRepresentation(xfer, param).good());
  ASSERT_TRUE(f.getDataset()->canWriteXfer(xfer));
  ASSERT_TRUE(f.saveFile(out.c_str(), xfer).good());
}

struct Lossless {
  const char* name;
  E_TransferSyntax xfer;
};

void PrintTo(const Lossless& l, std::ostream* os) { *os << l.name; }

class DecompressPixels : public ::testing::TestWithParam<Lossless> {};

TEST_P(DecompressPixels, CompressedCtReadsExactlyAsTheOriginal) {
  TempDir dir;
  const std::string path = dir.path().string() + "/ct.dcm";
  const DJ_RPLossless jpeg_lossless(1, 0);  // predictor 1, no point transform: lossless
  const DJLSRepresentationParameter jpeg_ls(0, OFTrue);
  const DcmRepresentationParameter* param = nullptr;
  if (GetParam().xfer == EXS_JPEGProcess14SV1) param = &jpeg_lossless;
  if (GetParam().xfer == EXS_JPEGLSLossless) param = &jpeg_ls;
  write_compressed(GetParam().xfer, param, path);
  DcmFileFormat check;
  ASSERT_TRUE(check.loadFile(path.c_str()).good());
  ASSERT_TRUE(DcmXfer(check.getDataset()->getOriginalXfer()).isEncapsulated()) << "the test file is not compressed";

  Result<SeriesImage> original = read_ct(data_dir("dicom/CT_small.dcm"));
  Result<SeriesImage> compressed = read_ct(path);
  ASSERT_TRUE(original.ok()) << original.status().to_string();
  ASSERT_TRUE(compressed.ok()) << compressed.status().to_string();
  EXPECT_EQ(compressed->image.geometry.dims, original->image.geometry.dims);
  EXPECT_EQ(compressed->image.geometry.origin_mm, original->image.geometry.origin_mm);
  ASSERT_EQ(compressed->image.voxels.size(), original->image.voxels.size());
  EXPECT_TRUE(compressed->image.voxels == original->image.voxels) << GetParam().name << " changed pixel values";
}

INSTANTIATE_TEST_SUITE_P(Lossless, DecompressPixels,
                         ::testing::Values(Lossless{"JpegLosslessSV1", EXS_JPEGProcess14SV1},
                                           Lossless{"JpegLsLossless", EXS_JPEGLSLossless},
                                           Lossless{"Rle", EXS_RLELossless}),
                         [](const ::testing::TestParamInfo<Lossless>& i) { return std::string(i.param.name); });

// The JPEG-LS file relabelled as JPEG 2000: encapsulated, and no decoder for it here.
TEST(DecompressPixelsRefused, JpegTwoThousandIsUnimplementedNamingFileAndSyntax) {
  TempDir dir;
  const std::string jls = dir.path().string() + "/jls.dcm", j2k = dir.path().string() + "/j2k.dcm";
  const DJLSRepresentationParameter jpeg_ls(0, OFTrue);
  write_compressed(EXS_JPEGLSLossless, &jpeg_ls, jls);
  DcmFileFormat f;
  ASSERT_TRUE(f.loadFile(jls.c_str()).good());
  ASSERT_TRUE(
      f.getMetaInfo()->putAndInsertString(DCM_TransferSyntaxUID, UID_JPEG2000LosslessOnlyTransferSyntax).good());
  ASSERT_TRUE(
      f.saveFile(j2k.c_str(), EXS_Unknown, EET_UndefinedLength, EGL_recalcGL, EPD_noChange, 0, 0, EWM_dontUpdateMeta)
          .good());
  Result<SeriesImage> r = read_ct(j2k);
  ASSERT_EQ(r.status().code(), StatusCode::kUnimplemented) << r.status().to_string();
  EXPECT_NE(r.status().message().find("j2k.dcm"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("JPEG 2000"), std::string::npos) << r.status().message();
}

TEST(DecompressPixelsRefused, CorruptJpegStreamIsDataLossNamingTheFile) {
  TempDir dir;
  const std::string path = dir.path().string() + "/broken.dcm";
  const DJ_RPLossless jpeg_lossless(1, 0);
  write_compressed(EXS_JPEGProcess14SV1, &jpeg_lossless, path);
  // Break the JPEG stream's start-of-image marker (FF D8 FF): the decoder cannot start. (Garbage in
  // the middle of a lossless stream is not detected by libjpeg: it decodes to other values.)
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t soi = bytes.find(std::string("\xFF\xD8\xFF", 3));
  ASSERT_NE(soi, std::string::npos);
  bytes[soi] = bytes[soi + 1] = '\0';
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  Result<SeriesImage> r = read_ct(path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kDataLoss) << r.status().to_string();
  EXPECT_NE(r.status().message().find("broken.dcm"), std::string::npos) << r.status().message();
}

}  // namespace
}  // namespace soiq::dicom
