// read_vtk_xml_polydata: soiq decodes a .vtp's arrays itself (VTK's reader allocates what the file
// claims). VTK's writer makes the files in every encoding it has and VTK's reader says what they
// hold: the oracle for well-formed files. Hostile files are built by hand and must be refused
// with a message, before anything near their claimed sizes is allocated.
#include "core/io/vtk_xml_polydata.h"

#include <gtest/gtest.h>
#include <vtkBase64Utilities.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStripper.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <zlib.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/geometry/primitives.h"
#include "core/io/parse_mesh.h"
#include "tests/core/io/io_test_files.h"
#include "tests/core/io/vtk_mesh_oracle.h"

namespace soiq {
namespace {

// A sphere whose polygons are partly strips, so both cell sections are exercised.
vtkSmartPointer<vtkPolyData> sphere_with_strips(bool double_points) {
  auto sphere = to_vtk_poly_data(uv_sphere({1.25, -3.5, 7.0}, 10.3, 7, 13));
  if (!double_points) {
    vtkNew<vtkPoints> single;
    single->SetDataTypeToFloat();
    for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i) single->InsertNextPoint(sphere->GetPoint(i));
    sphere->SetPoints(single);
  }
  vtkNew<vtkStripper> stripper;
  stripper->SetInputData(sphere);
  stripper->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(stripper->GetOutput());
  // Keep a few plain polygons beside the strips.
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell({0, 1, 2});
  polys->InsertNextCell({3, 4, 5, 6});
  out->SetPolys(polys);
  return out;
}

void expect_same_cells(vtkCellArray* vtk, const VtkXmlCells& ours, const std::string& label) {
  ASSERT_EQ(ours.offsets.size(), size_t(vtk->GetNumberOfCells() + 1)) << label;
  ASSERT_EQ(ours.connectivity.size(), size_t(vtk->GetNumberOfConnectivityIds())) << label;
  for (size_t i = 0; i < ours.offsets.size(); ++i)
    ASSERT_EQ(ours.offsets[i], vtk->GetOffsetsArray()->GetComponent(vtkIdType(i), 0)) << label << " offset " << i;
  for (size_t i = 0; i < ours.connectivity.size(); ++i)
    ASSERT_EQ(ours.connectivity[i], vtk->GetConnectivityArray()->GetComponent(vtkIdType(i), 0)) << label << " id " << i;
}

// Ours against VTK's reader on the same bytes: identical points (bit for bit) and cells.
void expect_same_as_vtk(const std::string& bytes, const std::string& label) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->ReadFromInputStringOn();
  reader->SetInputString(bytes);
  reader->Update();
  vtkPolyData* vtk = reader->GetOutput();
  ASSERT_GT(vtk->GetNumberOfPoints(), 0) << label;

  const auto ours = read_vtk_xml_polydata(bytes, "sphere.vtp");
  ASSERT_TRUE(ours.ok()) << label << ": " << ours.status().to_string();
  ASSERT_EQ(ours->points.size(), size_t(3 * vtk->GetNumberOfPoints())) << label;
  for (vtkIdType i = 0; i < vtk->GetNumberOfPoints(); ++i) {
    double p[3];
    vtk->GetPoint(i, p);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(ours->points[size_t(3 * i + k)], p[k]) << label << " point " << i;
  }
  expect_same_cells(vtk->GetPolys(), ours->polys, label + " polys");
  expect_same_cells(vtk->GetStrips(), ours->strips, label + " strips");
}

TEST(VtkXmlPolyData, EveryEncodingOfVtksWriterDecodesAsVtksReaderReadsIt) {
  int variants = 0;
  for (int mode : {vtkXMLWriter::Ascii, vtkXMLWriter::Binary, vtkXMLWriter::Appended})
    for (bool encode_appended : {false, true})
      for (int compressor : {vtkXMLWriter::NONE, vtkXMLWriter::ZLIB, vtkXMLWriter::LZ4, vtkXMLWriter::LZMA})
        for (int header : {vtkXMLWriter::UInt32, vtkXMLWriter::UInt64})
          for (int order : {vtkXMLWriter::LittleEndian, vtkXMLWriter::BigEndian})
            for (int ids : {vtkXMLWriter::Int32, vtkXMLWriter::Int64})
              for (bool double_points : {false, true}) {
                if (mode != vtkXMLWriter::Appended && encode_appended) continue;
                if (mode == vtkXMLWriter::Ascii && compressor != vtkXMLWriter::NONE) continue;
                vtkNew<vtkXMLPolyDataWriter> writer;
                writer->SetInputData(sphere_with_strips(double_points));
                writer->WriteToOutputStringOn();
                writer->SetDataMode(mode);
                writer->SetEncodeAppendedData(encode_appended);
                writer->SetCompressorType(compressor);
                writer->SetBlockSize(256);  // several compressed blocks per array
                // The fastest level: the default (5) makes LZMA zero a dictionary of megabytes per
                // 256-byte block, 84 s of this test under the sanitizers. Every level decodes alike.
                writer->SetCompressionLevel(1);
                writer->SetHeaderType(header);
                writer->SetByteOrder(order);
                writer->SetIdType(ids);
                ASSERT_EQ(writer->Write(), 1);
                const std::string label =
                    "mode " + std::to_string(mode) + " base64 " + std::to_string(encode_appended) + " compressor " +
                    std::to_string(compressor) + " header " + std::to_string(header) + " order " +
                    std::to_string(order) + " ids " + std::to_string(ids) + " double " + std::to_string(double_points);
                expect_same_as_vtk(writer->GetOutputString(), label);
                ++variants;
              }
  EXPECT_EQ(variants, 2 * 2 * 2 * 2 * (1 + 4 + 2 * 4));
}

TEST(VtkXmlPolyData, SeveralPiecesAreJoinedWithTheirPointIndicesShifted) {
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(sphere_with_strips(false));
  writer->WriteToOutputStringOn();
  writer->SetNumberOfPieces(3);
  ASSERT_EQ(writer->Write(), 1);
  expect_same_as_vtk(writer->GetOutputString(), "three pieces");
}

std::string base64(const std::string& bytes) {
  std::string out(bytes.size() * 4 / 3 + 8, '\0');
  const unsigned long n = vtkBase64Utilities::Encode(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(),
                                                     reinterpret_cast<unsigned char*>(out.data()));
  out.resize(n);
  return out;
}

template <typename T>
std::string raw(std::initializer_list<T> values) {
  std::string out;
  for (T v : values) out.append(reinterpret_cast<const char*>(&v), sizeof(T));
  return out;
}

// A one-triangle .vtp with the given DataArray bodies (each a complete <DataArray ...>...</DataArray>).
std::string vtp(const std::string& points, const std::string& offsets, const std::string& connectivity,
                const std::string& file_attributes = "", const std::string& appended = "", int polys = 1) {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" " +
         file_attributes + ">\n<PolyData>\n<Piece NumberOfPoints=\"3\" NumberOfPolys=\"" + std::to_string(polys) +
         "\">\n<Points>" + points + "</Points>\n<Polys>" + offsets + connectivity +
         "</Polys>\n</Piece>\n</PolyData>\n" + appended + "</VTKFile>\n";
}

const std::string kPoints =
    "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray>";
const std::string kOffsets = "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray>";
const std::string kConnectivity = "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>";

std::string binary_array(const char* type, const char* name, const std::string& header_and_data) {
  return std::string("<DataArray type=\"") + type + "\" Name=\"" + name + "\" format=\"binary\">" +
         base64(header_and_data) + "</DataArray>";
}

void expect_refused(const std::string& bytes, StatusCode code, const std::string& words) {
  const auto r = read_vtk_xml_polydata(bytes, "hostile.vtp");
  ASSERT_FALSE(r.ok()) << "accepted: " << bytes.substr(0, 400);
  EXPECT_EQ(r.status().code(), code) << r.status().to_string();
  EXPECT_NE(r.status().message().find(words), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("hostile.vtp"), std::string::npos) << r.status().message();
  EXPECT_EQ(r.status().message().find('\n'), std::string::npos) << r.status().message();
}

TEST(VtkXmlPolyData, HandBuiltTriangleIsRead) {
  const auto r = read_vtk_xml_polydata(vtp(kPoints, kOffsets, kConnectivity), "t.vtp");
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->points, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(r->polys.offsets, (std::vector<int64_t>{0, 3}));
  EXPECT_EQ(r->polys.connectivity, (std::vector<int64_t>{0, 1, 2}));
}

// The fuzzer's find: VTK 9.1 allocated 768 GB for this 1 KB file.
TEST(VtkXmlPolyData, TheFileThatAskedVtkFor768GbIsRefused) {
  const std::string bytes = testing_io::file_bytes(
      testing_io::data_path("../../fuzz/regressions/fuzz_vtk_polydata/xml_array_header_768gb.vtp"));
  ASSERT_LT(bytes.size(), 2000u);
  const auto r = read_vtk_xml_polydata(bytes, "hostile.vtp");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
}

TEST(VtkXmlPolyData, OffsetsClaimingMoreThanTheConnectivityHoldsAreRefused) {
  // The shape of the fuzzer's find: VTK sizes the connectivity by the last offset.
  const std::string offsets = binary_array("Int64", "offsets", raw<uint32_t>({8}) + raw<int64_t>({int64_t(1) << 40}));
  expect_refused(vtp(kPoints, offsets, kConnectivity), StatusCode::kInvalidArgument,
                 "holds 3 values where 1099511627776 are expected");
}

TEST(VtkXmlPolyData, HeaderClaimingMoreBytesThanFollowIsRefused) {
  const std::string connectivity =
      binary_array("Int32", "connectivity", raw<uint32_t>({0xFFFFFFF0u}) + raw<int32_t>({0, 1, 2}));
  expect_refused(vtp(kPoints, kOffsets, connectivity), StatusCode::kInvalidArgument,
                 "claims 4294967280 bytes but only");
}

TEST(VtkXmlPolyData, CompressedBlockCountBeyondTheBytesIsRefused) {
  const std::string connectivity =
      binary_array("Int32", "connectivity", raw<uint32_t>({0x40000000u, 65536, 0, 12}) + std::string(12, 'x'));
  expect_refused(vtp(kPoints, kOffsets, connectivity, "compressor=\"vtkZLibDataCompressor\""),
                 StatusCode::kInvalidArgument, "compressed blocks");
}

TEST(VtkXmlPolyData, CompressedSizeDeclaredBeyondAnyRealSurfaceIsRefused) {
  // One block said to inflate to 4 GB from 12 bytes: refused before inflating.
  const std::string connectivity =
      binary_array("Int32", "connectivity", raw<uint32_t>({1, 0xFFFFFFFFu, 0, 12}) + std::string(12, 'x'));
  expect_refused(vtp(kPoints, kOffsets, connectivity, "compressor=\"vtkZLibDataCompressor\""),
                 StatusCode::kResourceExhausted, "declares 4294967295 bytes once decompressed");
}

TEST(VtkXmlPolyData, ARealDecompressionBombIsRefused) {
  // 64 MB of zeros deflate to ~64 KB: honest zlib, but more than 64 times the file.
  const std::string zeros(64 << 20, '\0');
  uLongf size = compressBound(uLong(zeros.size()));
  std::string deflated(size, '\0');
  ASSERT_EQ(compress2(reinterpret_cast<Bytef*>(deflated.data()), &size, reinterpret_cast<const Bytef*>(zeros.data()),
                      uLong(zeros.size()), 9),
            Z_OK);
  deflated.resize(size);
  const std::string header = raw<uint32_t>({1, uint32_t(zeros.size()), 0, uint32_t(deflated.size())});
  const std::string connectivity = "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"binary\">" +
                                   base64(header) + base64(deflated) + "</DataArray>";
  expect_refused(vtp(kPoints, kOffsets, connectivity, "compressor=\"vtkZLibDataCompressor\""),
                 StatusCode::kResourceExhausted, "more than a surface file of this size can hold");
}

TEST(VtkXmlPolyData, CorruptCompressedBlockIsRefused) {
  const std::string header = raw<uint32_t>({1, 12, 0, 12});
  const std::string connectivity = "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"binary\">" +
                                   base64(header) + base64(std::string(12, 'x')) + "</DataArray>";
  expect_refused(vtp(kPoints, kOffsets, connectivity, "compressor=\"vtkZLibDataCompressor\""),
                 StatusCode::kInvalidArgument, "connectivity");
}

TEST(VtkXmlPolyData, MalformedArraysAndAttributesAreRefused) {
  struct Case {
    std::string bytes;
    std::string words;
  };
  const std::string nan_points =
      "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 nan 1 0 0 0 1 0</DataArray>";
  const std::string short_points =
      "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1</DataArray>";
  const std::string long_points =
      "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 5</DataArray>";
  const std::string two_components =
      "<DataArray type=\"Float32\" NumberOfComponents=\"2\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray>";
  const std::string string_points =
      "<DataArray type=\"String\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray>";
  const std::string float_ids = "<DataArray type=\"Float32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>";
  const std::string id_out_of_range =
      "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 3</DataArray>";
  const std::string two_offsets = "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3 1</DataArray>";
  const std::string appended_past_end =
      "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"appended\" offset=\"99999\"/>";
  const std::string bad_base64 =
      "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"binary\">DAAA*AAA</DataArray>";
  const std::vector<Case> cases{
      {"this is not xml", "cannot read mesh 'hostile.vtp'"},
      {"<?xml version=\"1.0\"?><VTKFile type=\"ImageData\"></VTKFile>", "not a VTK XML PolyData file"},
      {vtp(nan_points, kOffsets, kConnectivity), "'nan', not a finite number"},
      {vtp(short_points, kOffsets, kConnectivity), "holds 8 values where 9 are expected"},
      {vtp(two_components, kOffsets, kConnectivity), "has 2 components, 3 expected"},
      {vtp(string_points, kOffsets, kConnectivity), "has type 'String'"},
      {vtp(kPoints, kOffsets, float_ids), "must hold integers, not Float32"},
      {vtp(kPoints, kOffsets, id_out_of_range), "face index 3 out of range (it has 3 vertices)"},
      {vtp(kPoints, two_offsets, kConnectivity, "", "", 2), "offsets decrease (1 after 3)"},
      {vtp(kPoints, kOffsets, kConnectivity, "compressor=\"vtkFancyCompressor\""), "vtkFancyCompressor"},
      {vtp(kPoints, kOffsets, kConnectivity, "header_type=\"UInt16\""), "UInt16"},
      {vtp(kPoints, kOffsets, appended_past_end, "", "<AppendedData encoding=\"raw\">_abc</AppendedData>"),
       "offset past the end of the file"},
      {vtp(kPoints, kOffsets, appended_past_end), "the file has no AppendedData"},
      {vtp(kPoints, kOffsets, bad_base64), "not base64"},
      {vtp(kPoints, kOffsets, kConnectivity, "", "", 7), "holds 1 values where 7 are expected"},
      {vtp(long_points, kOffsets, kConnectivity), "holds more than the 9 values expected"},
      {vtp(kPoints, kOffsets, "<DataArray type=\"Int32\" Name=\"conn\" format=\"ascii\">0 1 2</DataArray>"),
       "needs DataArrays named \"offsets\" and \"connectivity\""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.words);
    expect_refused(c.bytes, StatusCode::kInvalidArgument, c.words);
  }
}

TEST(VtkXmlPolyData, MoreThan2To31PointsIsResourceExhaustedBeforeReading) {
  std::string bytes = vtp(kPoints, kOffsets, kConnectivity);
  const std::string from = "NumberOfPoints=\"3\"";
  bytes.replace(bytes.find(from), from.size(), "NumberOfPoints=\"3000000000\"");
  expect_refused(bytes, StatusCode::kResourceExhausted, "more than 2^31 vertices");
}

TEST(VtkXmlPolyData, ParseMeshTriangulatesWhatWasDecoded) {
  const auto mesh = parse_mesh(vtp(kPoints, kOffsets, kConnectivity), "vtp", /*ras=*/false, "t.vtp");
  ASSERT_TRUE(mesh.ok()) << mesh.status().to_string();
  ASSERT_EQ(mesh->triangles.size(), 1u);
  EXPECT_EQ(mesh->vertices_mm.size(), 3u);
}

}  // namespace
}  // namespace soiq
