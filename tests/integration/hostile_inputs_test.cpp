// Hostile and careless inputs sent to a real soiqd: each gets a precise status and a one-line
// message, soiqd keeps serving, and no record changes.

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
#include <utility>

#include "core/geometry/primitives.h"
#include "core/geometry/surface_area_volume.h"
#include "tests/integration/service_fixture.h"

namespace soiq::testing {
namespace {

bool one_line(const Status& s) { return s.message().find('\n') == std::string::npos && !s.message().empty(); }

v1::UploadImageHeader image_header(const std::string& patient, const std::string& study, const std::string& series,
                                   const std::string& format) {
  v1::UploadImageHeader h;
  h.mutable_patient()->set_patient_id(patient);
  h.mutable_study()->set_study_uid(study);
  h.set_series_uid(series);
  h.set_modality("MR");
  h.set_format(format);
  return h;
}

// An attached 2x2x2 uint8 NRRD whose voxels are 1..8.
std::string small_nrrd() {
  return std::string("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n") +
         std::string("\x01\x02\x03\x04\x05\x06\x07\x08", 8);
}

class HostileInputs : public ServiceTest {
 protected:
  // soiqd answers and holds exactly `series` series and `structures` structures.
  void expect_serving_with(int64_t series, int64_t structures) {
    Result<v1::ServerInfo> info = client_->server_info();
    ASSERT_TRUE(info.ok()) << info.status().to_string();
    EXPECT_EQ(info->series(), series);
    EXPECT_EQ(info->structures(), structures);
  }
};

// The attack that read a TLS key: a header naming a server file as its voxel data. The file's
// bytes would come back through features and exports.
TEST_F(HostileInputs, ImageHeadersNamingAServerFileAreRefused) {
  const std::string secret = dir_.file("server_secret.key");
  std::ofstream(secret) << "-----BEGIN PRIVATE KEY-----";
  const std::string nrrd =
      "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 3 3\nencoding: raw\ndata file: " + secret + "\n\n";
  const std::string mha =
      "ObjectType = Image\nNDims = 3\nDimSize = 3 3 3\nElementType = MET_UCHAR\n"
      "ElementDataFile = " +
      secret + "\n";
  for (const auto& [format, bytes] : {std::pair{std::string("nrrd"), nrrd}, std::pair{std::string("mha"), mha}}) {
    Result<v1::UploadImageResponse> r = client_->upload_image_bytes(image_header("P", "S", "1.2.3", format), bytes);
    ASSERT_FALSE(r.ok()) << format;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
    EXPECT_NE(r.status().message().find("names a separate data file"), std::string::npos) << r.status().message();
    EXPECT_TRUE(one_line(r.status())) << r.status().message();
  }
  expect_serving_with(0, 0);
}

TEST_F(HostileInputs, NiftiWithVoxOffsetPastItsDataIsRefused) {
  // A NIfTI-1 header (348 bytes, magic n+1) announcing 4x4x4 uint8 voxels at byte 4000 of a
  // 416-byte file.
  std::string bytes(416, '\0');
  const int32_t sizeof_hdr = 348;
  const int16_t dim[8] = {3, 4, 4, 4, 1, 1, 1, 1};
  const int16_t datatype = 2, bitpix = 8;
  const float pixdim[8] = {1, 1, 1, 1, 0, 0, 0, 0};
  const float vox_offset = 4000;
  std::memcpy(bytes.data(), &sizeof_hdr, 4);
  std::memcpy(bytes.data() + 40, dim, sizeof dim);
  std::memcpy(bytes.data() + 70, &datatype, 2);
  std::memcpy(bytes.data() + 72, &bitpix, 2);
  std::memcpy(bytes.data() + 76, pixdim, sizeof pixdim);
  std::memcpy(bytes.data() + 108, &vox_offset, 4);
  std::memcpy(bytes.data() + 344, "n+1", 4);
  Result<v1::UploadImageResponse> r = client_->upload_image_bytes(image_header("P", "S", "1.2.4", "nii"), bytes);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  EXPECT_NE(r.status().message().find("vox_offset 4000"), std::string::npos) << r.status().message();
  EXPECT_TRUE(one_line(r.status()));
  expect_serving_with(0, 0);
}

// This PLY crashed soiqd inside VTK's reader (a vertex line with fewer values than declared).
TEST_F(HostileInputs, MalformedMeshesAreRefusedAndSoiqdKeepsServing) {
  ASSERT_TRUE(upload(uv_sphere({0, 0, 0}, 10, 12, 24), "P", "S", "kept").ok());
  const std::string short_ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n";
  const std::string nan_obj = "v 0 0 0\nv 1 0 nan\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n";
  const std::string junk_obj = "v 0 0 0\nv 5abc 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n";
  // VTK's XML reader, behind our checks: its complaint reaches the client as one line, without the
  // object addresses VTK prints.
  const std::string short_vtp =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"3\" "
      "NumberOfPolys=\"1\"><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 "
      "0 1 0</DataArray></Points><Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 "
      "2</DataArray><DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys></Piece>"
      "</PolyData></VTKFile>\n";
  for (const auto& [format, bytes, says] :
       {std::tuple{"ply", short_ply, "vertex has 2 values"}, std::tuple{"obj", nan_obj, "nan"},
        std::tuple{"obj", junk_obj, "5abc"}, std::tuple{"vtp", short_vtp, "hostile"}}) {
    v1::UploadSurfaceHeader h = surface_header("P", "S", "hostile", "");
    h.set_format(format);
    Result<v1::UploadSurfaceResponse> r = client_->upload_surface_bytes(h, bytes);
    ASSERT_FALSE(r.ok()) << format;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
    EXPECT_NE(r.status().message().find(says), std::string::npos) << r.status().message();
    EXPECT_TRUE(one_line(r.status())) << r.status().message();
    EXPECT_EQ(r.status().message().find("0x"), std::string::npos) << r.status().message();
  }
  expect_serving_with(0, 1);
}

// VTK 9.1's XML reader allocated what a .vtp's arrays claim: 768 GB for a 1 KB file the fuzzer
// found, and a compressed block may declare any size. soiq decodes the arrays itself and compares
// every claim with the bytes there are.
TEST_F(HostileInputs, VtpArraysClaimingGigabytesAreRefused) {
  std::ifstream in(std::string(SOIQ_TEST_DATA_DIR) +
                   "/../../fuzz/regressions/fuzz_vtk_polydata/xml_array_header_768gb.vtp");
  const std::string fuzzed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(fuzzed.empty());
  // A zlib-compressed connectivity whose one block claims 4 GB from 12 bytes ("AQAAAP////8AAAAADAAAAA==" is the
  // header 1, 0xFFFFFFFF, 0, 12 in little-endian UInt32 words).
  const std::string bomb =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" compressor=\"vtkZLibDataCompressor\"><PolyData><Piece "
      "NumberOfPoints=\"3\" NumberOfPolys=\"1\"><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" "
      "format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points><Polys><DataArray type=\"Int32\" Name=\"offsets\" "
      "format=\"ascii\">3</DataArray><DataArray type=\"Int32\" Name=\"connectivity\" format=\"binary\">"
      "AQAAAP////8AAAAADAAAAA==eHh4eHh4eHh4eHh4</DataArray></Polys></Piece></PolyData></VTKFile>\n";
  for (const auto& [bytes, code, says] :
       {std::tuple{fuzzed, StatusCode::kInvalidArgument, "hostile"},
        std::tuple{bomb, StatusCode::kResourceExhausted, "declares 4294967295 bytes once decompressed"}}) {
    v1::UploadSurfaceHeader h = surface_header("P", "S", "hostile", "");
    h.set_format("vtp");
    Result<v1::UploadSurfaceResponse> r = client_->upload_surface_bytes(h, bytes);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), code) << r.status().to_string();
    EXPECT_NE(r.status().message().find(says), std::string::npos) << r.status().message();
    EXPECT_TRUE(one_line(r.status())) << r.status().message();
  }
  expect_serving_with(0, 0);
}

// An upload naming another patient's series used to move the series (and its images) over.
TEST_F(HostileInputs, ASeriesNeverChangesPatient) {
  ASSERT_TRUE(client_->upload_image_bytes(image_header("P1", "S1", "1.2.5", "nrrd"), small_nrrd()).ok());
  Result<v1::UploadImageResponse> r =
      client_->upload_image_bytes(image_header("P2", "S2", "1.2.5", "nrrd"), small_nrrd());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition) << r.status().to_string();
  EXPECT_NE(r.status().message().find("'P1'"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("'P2'"), std::string::npos) << r.status().message();
  EXPECT_EQ(client_->get_patient("P2").status().code(), StatusCode::kNotFound);
  Result<v1::Study> s1 = client_->get_study("S1");
  ASSERT_TRUE(s1.ok());
  EXPECT_EQ(s1->series_size(), 1);
  expect_serving_with(1, 0);
}

// A SEG whose NumberOfFrames is 0 reached a null frame pointer and killed soiqd; one truncated
// short of its frames overwrote a structure. Both are refused, and soiqd keeps serving.
TEST_F(HostileInputs, HostileSegsAreRefusedAndSoiqdKeepsServing) {
  const std::string source = std::string(SOIQ_TEST_DATA_DIR) + "/dicom/standard_seg.dcm";
  const std::string zero = dir_.file("zero_frames.dcm");
  const std::string cut = dir_.file("cut_frames.dcm");
  ASSERT_EQ(std::system(
                ("cp '" + source + "' '" + zero + "' && dcmodify -nb -m '(0028,0008)=0' '" + zero + "' >/dev/null 2>&1")
                    .c_str()),
            0);
  ASSERT_EQ(std::system(
                ("cp '" + source + "' '" + cut + "' && dcmodify -nb -m '(0028,0008)=400' '" + cut + "' >/dev/null 2>&1")
                    .c_str()),
            0);
  // The image series the fixture's frames lie on (make_standard_seg.py), so that reading gets as
  // far as the frames.
  std::string nrrd =
      "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 11 7 6\nspace: left-posterior-superior\n"
      "space directions: (0.9,0,0) (0,1.2,0) (0,0,3)\nspace origin: (10,-5.5,20)\nencoding: raw\n\n";
  nrrd += std::string(11 * 7 * 6, '\0');
  v1::UploadImageHeader h =
      image_header("SEG-FIXTURE", "1.2.826.0.1.3680043.8.498.9917.2", "1.2.826.0.1.3680043.8.498.9917.6", "nrrd");
  Result<v1::UploadImageResponse> image = client_->upload_image_bytes(h, nrrd);
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  for (const auto& [path, says] :
       {std::pair{zero, std::string("NumberOfFrames")}, std::pair{cut, std::string("truncated")}}) {
    Result<v1::ImportDicomResponse> r = client_->import_dicom({path});
    std::string message;
    if (r.ok()) {
      EXPECT_EQ(r->structures_size(), 0);
      ASSERT_GT(r->problems_size(), 0);
      message = r->problems(0).message();
    } else {
      EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
      message = r.status().message();
    }
    EXPECT_NE(message.find(says), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  expect_serving_with(1, 0);
}

// Identifiers and names that would break logs, CSV and DICOM (newlines, megabytes) are refused; a
// glob too long for SQLite is INVALID_ARGUMENT naming the field, not INTERNAL quoting SQL.
TEST_F(HostileInputs, OversizeAndControlCharacterTextIsRefused) {
  const TriangleMesh ball = uv_sphere({0, 0, 0}, 10, 12, 24);
  for (const auto& [patient, name, says] : {std::tuple{std::string(1 << 20, 'P'), std::string("ok"), "patient_id"},
                                            std::tuple{std::string("P\nX"), std::string("ok"), "control character"},
                                            std::tuple{std::string("P"), std::string(300, 'n'), "structure_name"},
                                            std::tuple{std::string("P"), std::string("a\tb"), "control character"}}) {
    Result<v1::UploadSurfaceResponse> r = upload(ball, patient, "S", name);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
    EXPECT_NE(r.status().message().find(says), std::string::npos) << r.status().message();
    EXPECT_TRUE(one_line(r.status()));
    EXPECT_LT(r.status().message().size(), 400u);
  }
  const std::string glob = "*" + std::string(100'000, 'a');
  Result<v1::ListStructuresResponse> listed = client_->list_structures(v1::ListStructuresRequest());
  ASSERT_TRUE(listed.ok());
  v1::ListStructuresRequest by_name;
  by_name.set_name_glob(glob);
  listed = client_->list_structures(by_name);
  EXPECT_EQ(listed.status().code(), StatusCode::kInvalidArgument) << listed.status().to_string();
  EXPECT_EQ(listed.status().message().find("SELECT"), std::string::npos) << listed.status().message();
  v1::QueryRequest q;
  q.mutable_stage1()->set_structure_name_glob(glob);
  Result<v1::QuerySummary> summary = client_->query(q, {});
  EXPECT_EQ(summary.status().code(), StatusCode::kInvalidArgument) << summary.status().to_string();
  EXPECT_NE(summary.status().message().find("stage1.structure_name_glob"), std::string::npos);
  EXPECT_EQ(summary.status().field(), "stage1.structure_name_glob");
  expect_serving_with(0, 0);
}

// Proto3 enums are open: a number no version of the API defines is refused, not read as a default.
TEST_F(HostileInputs, CoverageFractionRequestsThatCannotBeAnsweredAreRefused) {
  Result<v1::UploadSurfaceResponse> up = upload(uv_sphere({0, 0, 0}, 10, 24, 48), "P", "S", "ball");
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  auto ask = [&](int64_t id, int oversample, v1::VolumeEncoding encoding, v1::FractionType type) {
    v1::ConvertRequest c;
    c.set_structure_id(id);
    c.mutable_grid()->set_spacing_mm(1);
    c.set_oversample(oversample);
    c.set_encoding(encoding);
    c.set_fraction_type(type);
    return client_->convert(c, {});
  };
  const int64_t id = up->structure().id();
  auto refused = [](const Result<v1::ConvertSummary>& r, StatusCode code, const std::string& phrase) {
    EXPECT_EQ(r.status().code(), code) << r.status().to_string();
    EXPECT_NE(r.status().message().find(phrase), std::string::npos) << r.status().message();
  };
  refused(ask(id, 9, v1::NIFTI_GZ, v1::FRACTION_UINT8), StatusCode::kInvalidArgument,
          "1 to 8 (coverage fractions), not 9");
  refused(ask(id, -1, v1::NIFTI_GZ, v1::FRACTION_UINT8), StatusCode::kInvalidArgument, "not -1");
  refused(ask(id, 4, v1::RUNS, v1::FRACTION_UINT8), StatusCode::kInvalidArgument, "ask for NIFTI_GZ");
  refused(ask(id, 0, v1::NIFTI_GZ, v1::FRACTION_FLOAT32), StatusCode::kInvalidArgument, "set oversample to 1-8");
  refused(ask(id, 4, v1::NIFTI_GZ, static_cast<v1::FractionType>(7)), StatusCode::kInvalidArgument,
          "fraction_type: 7 is not a value");
  refused(ask(id + 1000, 4, v1::NIFTI_GZ, v1::FRACTION_UINT8), StatusCode::kNotFound, "");
  TriangleMesh open = uv_sphere({0, 0, 0}, 10, 12, 24);
  open.triangles.pop_back();
  Result<v1::UploadSurfaceResponse> robust = upload(open, "P", "S", "open", "", "stl", true);
  ASSERT_TRUE(robust.ok()) << robust.status().to_string();
  refused(ask(robust->structure().id(), 2, v1::NIFTI_GZ, v1::FRACTION_UINT8), StatusCode::kFailedPrecondition,
          "robust mode");
  // And the same sphere answered: the summary's volume is the sum of fractions, near the mesh's.
  Result<v1::ConvertSummary> ok = ask(id, 4, v1::NIFTI_GZ, v1::FRACTION_FLOAT32);
  ASSERT_TRUE(ok.ok()) << ok.status().to_string();
  EXPECT_EQ(ok->oversample(), 4);
  EXPECT_GT(ok->partial_voxels(), 0);
  EXPECT_GT(ok->nifti_bytes(), 0);
  const double mesh_volume = surface_area_volume(uv_sphere({0, 0, 0}, 10, 24, 48))->volume_mm3;
  EXPECT_NEAR(ok->volume_mm3(), mesh_volume, 0.01 * mesh_volume);
}

// A fractional SEG: oversample out of range before any lookup; an open surface has no fractions,
// which is said before that it also has no DICOM images to reference.
TEST_F(HostileInputs, FractionalSegRequestsThatCannotBeAnsweredAreRefused) {
  TriangleMesh open = uv_sphere({0, 0, 0}, 10, 12, 24);
  open.triangles.pop_back();
  Result<v1::UploadSurfaceResponse> robust = upload(open, "P", "S", "open", "", "stl", true);
  ASSERT_TRUE(robust.ok()) << robust.status().to_string();
  auto ask = [&](int oversample) {
    v1::ExportSegRequest e;
    e.add_structure_ids(robust->structure().id());
    e.set_oversample(oversample);
    return client_->export_seg(e, dir_.file("refused.dcm"));
  };
  for (const int n : {9, -1}) {
    const Result<v1::SegInfo> r = ask(n);
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
    EXPECT_NE(r.status().message().find("1 to 8 (a FRACTIONAL SEG of coverage fractions), not " + std::to_string(n)),
              std::string::npos)
        << r.status().message();
  }
  const Result<v1::SegInfo> r = ask(4);
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition) << r.status().to_string();
  EXPECT_NE(r.status().message().find("robust mode"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("export a binary SEG"), std::string::npos) << r.status().message();
  EXPECT_FALSE(std::filesystem::exists(dir_.file("refused.dcm")));
}

TEST_F(HostileInputs, UnknownEnumValuesAreRefused) {
  Result<v1::UploadSurfaceResponse> up = upload(uv_sphere({0, 0, 0}, 10, 12, 24), "P", "S", "ball");
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  v1::ConvertRequest c;
  c.set_structure_id(up->structure().id());
  c.mutable_grid()->set_spacing_mm(1);
  c.set_fill_rule(static_cast<v1::FillRule>(77));
  Result<v1::ConvertSummary> r = client_->convert(c, {});
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  EXPECT_NE(r.status().message().find("fill_rule: 77 is not a value this server knows"), std::string::npos)
      << r.status().message();
  v1::FeaturesRequest f;
  f.set_structure_id(up->structure().id());
  f.set_interpolation(static_cast<v1::Interpolation>(-3));
  EXPECT_EQ(client_->compute_features(f).status().code(), StatusCode::kInvalidArgument);
  v1::UploadSurfaceHeader h = surface_header("P", "S", "ras?", "");
  h.set_format("stl");
  h.set_coordinates(static_cast<v1::CoordinateSystem>(9));
  EXPECT_EQ(client_->upload_surface(h, write_mesh_file(uv_sphere({0, 0, 0}, 5, 8, 16), "stl")).status().code(),
            StatusCode::kInvalidArgument);
  expect_serving_with(0, 1);
}

}  // namespace
}  // namespace soiq::testing
