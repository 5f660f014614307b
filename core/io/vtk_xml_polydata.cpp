#include "core/io/vtk_xml_polydata.h"

#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <charconv>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

#include "core/io/vtk_messages.h"
#include "core/io/vtk_xml_data_array.h"

namespace soiq {
namespace {

// A decompression bomb must not be able to ask for more than this multiple of its own size. Real
// surfaces compress 1.5-6 times (float coordinates hardly, sorted indices well).
constexpr uint64_t kMaxExpansion = 64;
constexpr uint64_t kExpansionAllowance = 1ull << 20;

struct FileEncoding {
  bool big_endian = false;
  bool header_64 = false;
  VtkXmlCompressor compressor = VtkXmlCompressor::kNone;
  std::optional<std::string_view> appended;  // from the byte after AppendedData's '_'
  bool appended_base64 = false;
};

std::string text_or_empty(const char* s) { return s != nullptr ? s : ""; }

// An unsigned whole-number attribute; `fallback` when absent.
Result<uint64_t> count_attribute(vtkXMLDataElement* e, const char* attribute, uint64_t fallback,
                                 const std::string& what) {
  const char* text = e->GetAttribute(attribute);
  if (text == nullptr) return fallback;
  uint64_t v = 0;
  const char* end = text + std::strlen(text);
  const auto [ptr, ec] = std::from_chars(text, end, v);
  if (ec != std::errc() || ptr != end || ptr == text)
    return invalid_argument(what + " has " + attribute + "=\"" + std::string(text).substr(0, 32) + "\", not a count");
  return v;
}

Result<FileEncoding> file_encoding(vtkXMLDataElement* root, vtkXMLDataParser* parser, std::string_view bytes,
                                   const std::string& what) {
  FileEncoding f;
  const std::string order = text_or_empty(root->GetAttribute("byte_order"));
  if (order == "BigEndian")
    f.big_endian = true;
  else if (!order.empty() && order != "LittleEndian")
    return invalid_argument(what + " has byte_order \"" + order.substr(0, 32) + "\"");
  const std::string header = text_or_empty(root->GetAttribute("header_type"));
  if (header == "UInt64")
    f.header_64 = true;
  else if (!header.empty() && header != "UInt32")
    return invalid_argument(what + " has header_type \"" + header.substr(0, 32) + "\" (UInt32 or UInt64 expected)");
  const std::string compressor = text_or_empty(root->GetAttribute("compressor"));
  if (compressor == "vtkZLibDataCompressor")
    f.compressor = VtkXmlCompressor::kZlib;
  else if (compressor == "vtkLZ4DataCompressor")
    f.compressor = VtkXmlCompressor::kLz4;
  else if (compressor == "vtkLZMADataCompressor")
    f.compressor = VtkXmlCompressor::kLzma;
  else if (!compressor.empty())
    return invalid_argument(what + " is compressed with \"" + compressor.substr(0, 40) +
                            "\"; soiq reads vtkZLibDataCompressor, vtkLZ4DataCompressor and vtkLZMADataCompressor");
  if (vtkXMLDataElement* appended = root->FindNestedElementWithName("AppendedData")) {
    const std::string encoding = text_or_empty(appended->GetAttribute("encoding"));
    if (encoding == "base64")
      f.appended_base64 = true;
    else if (encoding != "raw")
      return invalid_argument(what + " has AppendedData encoding \"" + encoding.substr(0, 32) + "\" (raw or base64)");
    const vtkTypeInt64 at = parser->GetAppendedDataPosition();
    if (at < 0 || uint64_t(at) > bytes.size()) return invalid_argument(what + " has no data after AppendedData's '_'");
    f.appended = bytes.substr(size_t(at));
  }
  return f;
}

vtkXMLDataElement* array_named(vtkXMLDataElement* parent, const char* name) {
  for (int i = 0; i < parent->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = parent->GetNestedElement(i);
    const char* n = e->GetAttribute("Name");
    if (std::strcmp(e->GetName(), "DataArray") == 0 && n != nullptr && std::strcmp(n, name) == 0) return e;
  }
  return nullptr;
}

// The text of an element holding inline data: VTK's parser keeps no text for DataArray elements,
// only where they start, so the text is cut from the file: past the start tag's '>' (quoted
// attribute values skipped, as they may hold '>') up to the next '<'. Neither numbers nor base64
// contain '<'. A self-closing element has none.
Result<std::string_view> inline_text(vtkXMLDataElement* array, std::string_view bytes, const std::string& what) {
  const vtkTypeInt64 start = array->GetXMLByteIndex();
  if (start < 0 || uint64_t(start) >= bytes.size()) return invalid_argument(what + " cannot be located in the file");
  char quote = 0;
  for (size_t i = size_t(start); i < bytes.size(); ++i) {
    const char c = bytes[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      if (bytes[i - 1] == '/') return std::string_view();
      const size_t end = bytes.find('<', i + 1);
      return bytes.substr(i + 1, (end == std::string_view::npos ? bytes.size() : end) - (i + 1));
    }
  }
  return invalid_argument(what + " has an unterminated start tag");
}

// Where a DataArray's data is, and how it is encoded.
Result<std::pair<std::string_view, VtkXmlArrayEncoding>> array_source(vtkXMLDataElement* array, const FileEncoding& f,
                                                                      std::string_view bytes, const std::string& what) {
  VtkXmlArrayEncoding e;
  e.type = text_or_empty(array->GetAttribute("type"));
  e.big_endian = f.big_endian;
  e.header_64 = f.header_64;
  e.compressor = f.compressor;
  const std::string format = text_or_empty(array->GetAttribute("format"));
  if (format == "ascii" || format == "binary") {
    e.ascii = format == "ascii";
    SOIQ_ASSIGN_OR_RETURN(const std::string_view text, inline_text(array, bytes, what));
    return std::pair{text, e};
  }
  if (format != "appended") {
    return invalid_argument(what + " has format \"" + format.substr(0, 32) + "\" (ascii, binary or appended)");
  }
  if (!f.appended) return invalid_argument(what + " is appended but the file has no AppendedData");
  SOIQ_ASSIGN_OR_RETURN(const uint64_t offset, count_attribute(array, "offset", 0, what));
  if (array->GetAttribute("offset") == nullptr) return invalid_argument(what + " is appended but has no offset");
  if (offset > f.appended->size()) return invalid_argument(what + " has an offset past the end of the file");
  e.base64 = f.appended_base64;
  return std::pair{f.appended->substr(size_t(offset)), e};
}

Status check_components(vtkXMLDataElement* array, uint64_t components, const std::string& what) {
  SOIQ_ASSIGN_OR_RETURN(const uint64_t n, count_attribute(array, "NumberOfComponents", 1, what));
  if (n != components)
    return invalid_argument(what + " has " + std::to_string(n) + " components, " + std::to_string(components) +
                            " expected");
  return ok_status();
}

// One piece's polygons or strips, appended to `out` with point indices shifted by `first_point`.
Status read_cells(vtkXMLDataElement* piece, const char* section, uint64_t cells, uint64_t points, int64_t first_point,
                  const FileEncoding& f, std::string_view bytes, uint64_t& budget, const std::string& what,
                  VtkXmlCells& out) {
  if (cells == 0) return ok_status();
  const std::string where = what + ": " + section;
  vtkXMLDataElement* element = piece->FindNestedElementWithName(section);
  if (element == nullptr)
    return invalid_argument(where + " is missing (the piece declares " + std::to_string(cells) + " of them)");
  vtkXMLDataElement* offsets_array = array_named(element, "offsets");
  vtkXMLDataElement* connectivity_array = array_named(element, "connectivity");
  if (offsets_array == nullptr || connectivity_array == nullptr)
    return invalid_argument(where + " needs DataArrays named \"offsets\" and \"connectivity\"");

  const std::string offsets_what = where + " offsets";
  SOIQ_RETURN_IF_ERROR(check_components(offsets_array, 1, offsets_what));
  SOIQ_ASSIGN_OR_RETURN(auto offsets_source, array_source(offsets_array, f, bytes, offsets_what));
  SOIQ_ASSIGN_OR_RETURN(
      std::vector<int64_t> offsets,
      decode_vtk_xml_integers(offsets_source.first, offsets_source.second, cells, budget, offsets_what));
  // The file leaves out the leading 0: each value is where a cell ends.
  int64_t previous = 0;
  for (int64_t o : offsets) {
    if (o < previous)
      return invalid_argument(offsets_what + " decrease (" + std::to_string(o) + " after " + std::to_string(previous) +
                              ")");
    previous = o;
  }

  const std::string connectivity_what = where + " connectivity";
  SOIQ_RETURN_IF_ERROR(check_components(connectivity_array, 1, connectivity_what));
  SOIQ_ASSIGN_OR_RETURN(auto connectivity_source, array_source(connectivity_array, f, bytes, connectivity_what));
  // The count is only compared with what the array holds; the array's own size bounds the memory.
  SOIQ_ASSIGN_OR_RETURN(std::vector<int64_t> connectivity,
                        decode_vtk_xml_integers(connectivity_source.first, connectivity_source.second,
                                                uint64_t(previous), budget, connectivity_what));
  for (int64_t id : connectivity) {
    if (id < 0 || uint64_t(id) >= points) {
      return invalid_argument(what + " has a face index " + std::to_string(id) + " out of range (it has " +
                              std::to_string(points) + " vertices)");
    }
  }

  const int64_t base = out.connectivity.size();
  for (int64_t o : offsets) out.offsets.push_back(base + o);
  for (int64_t id : connectivity) out.connectivity.push_back(first_point + id);
  return ok_status();
}

}  // namespace

Result<VtkXmlPolyData> read_vtk_xml_polydata(std::string_view bytes, const std::string& name) {
  const std::string what = "mesh '" + name + "'";
  VtkMessages messages;
  vtkNew<vtkXMLDataParser> parser;
  std::istringstream stream{std::string(bytes)};
  parser->SetStream(&stream);
  const int parsed = parser->Parse();
  vtkXMLDataElement* root = parser->GetRootElement();
  if (!parsed || root == nullptr || messages.has_error()) {
    const std::string why = messages.last_error();
    return invalid_argument("cannot read " + what + ": " + (why.empty() ? "not a VTK XML file" : why));
  }
  if (std::strcmp(root->GetName(), "VTKFile") != 0 || text_or_empty(root->GetAttribute("type")) != "PolyData")
    return invalid_argument(what + " is not a VTK XML PolyData file (<VTKFile type=\"PolyData\">)");
  vtkXMLDataElement* polydata = root->FindNestedElementWithName("PolyData");
  if (polydata == nullptr) return invalid_argument(what + " has no PolyData element");
  SOIQ_ASSIGN_OR_RETURN(const FileEncoding f, file_encoding(root, parser, bytes, what));

  uint64_t budget = kMaxExpansion * uint64_t(bytes.size()) + kExpansionAllowance;
  VtkXmlPolyData out;
  for (int i = 0; i < polydata->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* piece = polydata->GetNestedElement(i);
    if (std::strcmp(piece->GetName(), "Piece") != 0) continue;
    const std::string piece_what = what + " piece " + std::to_string(i);
    SOIQ_ASSIGN_OR_RETURN(const uint64_t points, count_attribute(piece, "NumberOfPoints", 0, piece_what));
    SOIQ_ASSIGN_OR_RETURN(const uint64_t polys, count_attribute(piece, "NumberOfPolys", 0, piece_what));
    SOIQ_ASSIGN_OR_RETURN(const uint64_t strips, count_attribute(piece, "NumberOfStrips", 0, piece_what));
    const uint64_t first_point = out.points.size() / 3;
    if (points > uint64_t(std::numeric_limits<int32_t>::max()) - first_point)
      return resource_exhausted(what + " has more than 2^31 vertices");
    if (points > 0) {
      vtkXMLDataElement* element = piece->FindNestedElementWithName("Points");
      vtkXMLDataElement* array = element != nullptr ? element->FindNestedElementWithName("DataArray") : nullptr;
      if (array == nullptr) return invalid_argument(piece_what + " declares points but has no Points DataArray");
      const std::string points_what = piece_what + " Points";
      SOIQ_RETURN_IF_ERROR(check_components(array, 3, points_what));
      SOIQ_ASSIGN_OR_RETURN(auto source, array_source(array, f, bytes, points_what));
      SOIQ_ASSIGN_OR_RETURN(std::vector<double> xyz,
                            decode_vtk_xml_reals(source.first, source.second, points * 3, budget, points_what));
      out.points.insert(out.points.end(), xyz.begin(), xyz.end());
    }
    SOIQ_RETURN_IF_ERROR(
        read_cells(piece, "Polys", polys, points, int64_t(first_point), f, bytes, budget, piece_what, out.polys));
    SOIQ_RETURN_IF_ERROR(
        read_cells(piece, "Strips", strips, points, int64_t(first_point), f, bytes, budget, piece_what, out.strips));
  }
  return out;
}

}  // namespace soiq
