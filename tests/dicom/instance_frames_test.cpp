// An original instance's frames and its re-encoding, as WADO-RS serves them (dicom/instance_frames.h,
// dicom/instance_transcode.h): CT_small's frame is the file's own Pixel Data bytes (at offset 6300,
// as pydicom finds them); the STS JPEG-LS
// MR decodes to the same frame as its Explicit VR Little Endian transcoding (which DCMTK reads back
// with the same attributes); wrong frame numbers, a binary SEG's frames and non-DICOM bytes are
// refused saying why.
#include "dicom/instance_frames.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "dicom/dicom_json_metadata.h"
#include "dicom/instance_transcode.h"
#include "dicom_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The first JPEG-LS file of STS_002's MR.
std::string jpegls_mr() {
  for (const auto& f : std::filesystem::directory_iterator(data_dir("sts/STS_002/dicom_jpegls/MR_T1/image")))
    return file_bytes(f.path().string());
  return "";
}

TEST(InstanceFrames, AnUncompressedFrameIsTheFilesOwnPixelBytes) {
  const std::string ct = file_bytes(data_dir("dicom/CT_small.dcm"));
  Result<std::vector<std::string>> frames = instance_frames(ct, {1});
  ASSERT_TRUE(frames.ok()) << frames.status().to_string();
  ASSERT_EQ(frames->size(), 1u);
  EXPECT_EQ(frames->at(0).size(), 128u * 128u * 2u);  // Rows x Columns x Bits Allocated / 8
  // Explicit VR Little Endian: the frame is the Pixel Data's 32 KiB as the file holds them (before
  // its trailing padding); no other run of the file's bytes could match them.
  EXPECT_EQ(ct.find(frames->at(0)), 6300u);
  EXPECT_EQ(instance_frames(ct, {})->size(), 1u);  // all of them
  EXPECT_EQ(instance_frames(ct, {1, 1})->size(), 2u);
}

TEST(InstanceFrames, ACompressedFileDecodesToTheFramesOfItsTranscoding) {
  const std::string mr = jpegls_mr();
  ASSERT_FALSE(mr.empty());
  EXPECT_EQ(transfer_syntax_of(mr).value(), "1.2.840.10008.1.2.4.80");  // JPEG-LS lossless
  Result<std::string> plain = as_explicit_little_endian(mr);
  ASSERT_TRUE(plain.ok()) << plain.status().to_string();
  EXPECT_EQ(transfer_syntax_of(*plain).value(), kExplicitVrLittleEndianUid);
  Result<std::vector<std::string>> decoded = instance_frames(mr, {1});
  ASSERT_TRUE(decoded.ok()) << decoded.status().to_string();
  EXPECT_EQ(instance_frames(*plain, {1}).value(), *decoded);
  // The same attributes, but for the Pixel Data's encoding.
  EXPECT_EQ(dicom_json_metadata(*plain, "x").value().size() > 100, true);
  const std::string uid_tag = "\"00080018\"";
  const std::string a = dicom_json_metadata(mr, "x").value(), b = dicom_json_metadata(*plain, "x").value();
  EXPECT_EQ(a.substr(a.find(uid_tag), 120), b.substr(b.find(uid_tag), 120));
  // A file in Explicit VR Little Endian already is sent as it is.
  EXPECT_EQ(as_explicit_little_endian(*plain).value(), *plain);
}

TEST(InstanceFrames, WhatCannotBeServedAsFramesIsRefusedSayingWhy) {
  const std::string ct = file_bytes(data_dir("dicom/CT_small.dcm"));
  for (const int64_t bad : {int64_t(0), int64_t(2)}) {
    Result<std::vector<std::string>> r = instance_frames(ct, {bad});
    EXPECT_EQ(r.status().code(), StatusCode::kNotFound);
    EXPECT_NE(r.status().message().find("has 1 frame"), std::string::npos) << r.status().message();
  }
  Result<std::vector<std::string>> seg = instance_frames(file_bytes(data_dir("dicom/standard_seg.dcm")), {1});
  EXPECT_EQ(seg.status().code(), StatusCode::kUnimplemented);
  EXPECT_NE(seg.status().message().find("1 bit"), std::string::npos) << seg.status().message();
  EXPECT_EQ(instance_frames("not DICOM at all", {1}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(transfer_syntax_of("not DICOM").status().code(), StatusCode::kInvalidArgument);
}

TEST(InstanceFrames, TheBulkDataPlaceholderBecomesTheAddressServed) {
  const std::string ct = file_bytes(data_dir("dicom/CT_small.dcm"));
  const std::string kept = dicom_json_metadata(ct, kBulkDataUriPlaceholder).value();
  const std::string served = with_bulk_data_uri(kept, "http://h/dicom-web/x/bulkdata");
  EXPECT_NE(served.find("\"7FE00010\":{\"vr\":\"OW\",\"BulkDataURI\":\"http://h/dicom-web/x/bulkdata\"}"),
            std::string::npos)
      << served.substr(served.size() - 200);
  EXPECT_EQ(served.find(kBulkDataUriPlaceholder), std::string::npos);
}

}  // namespace
}  // namespace soiq::dicom
