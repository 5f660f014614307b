#include "core/io/read_nrrd.h"

#include <bit>
#include <cmath>
#include <map>
#include <optional>

#include "core/io/geometry_from_axes.h"
#include "core/io/header_text.h"
#include "core/io/read_file_bytes.h"
#include "core/io/voxel_type.h"
#include "core/io/zlib_codec.h"

namespace soiq {
namespace {

std::optional<VoxelType> nrrd_voxel_type(const std::string& name) {
  static const std::map<std::string, VoxelType> kTypes = {{"signed char", VoxelType::kInt8},
                                                          {"int8", VoxelType::kInt8},
                                                          {"int8_t", VoxelType::kInt8},
                                                          {"uchar", VoxelType::kUint8},
                                                          {"unsigned char", VoxelType::kUint8},
                                                          {"uint8", VoxelType::kUint8},
                                                          {"uint8_t", VoxelType::kUint8},
                                                          {"short", VoxelType::kInt16},
                                                          {"short int", VoxelType::kInt16},
                                                          {"signed short", VoxelType::kInt16},
                                                          {"signed short int", VoxelType::kInt16},
                                                          {"int16", VoxelType::kInt16},
                                                          {"int16_t", VoxelType::kInt16},
                                                          {"ushort", VoxelType::kUint16},
                                                          {"unsigned short", VoxelType::kUint16},
                                                          {"unsigned short int", VoxelType::kUint16},
                                                          {"uint16", VoxelType::kUint16},
                                                          {"uint16_t", VoxelType::kUint16},
                                                          {"int", VoxelType::kInt32},
                                                          {"signed int", VoxelType::kInt32},
                                                          {"int32", VoxelType::kInt32},
                                                          {"int32_t", VoxelType::kInt32},
                                                          {"uint", VoxelType::kUint32},
                                                          {"unsigned int", VoxelType::kUint32},
                                                          {"uint32", VoxelType::kUint32},
                                                          {"uint32_t", VoxelType::kUint32},
                                                          {"float", VoxelType::kFloat32},
                                                          {"double", VoxelType::kFloat64}};
  const auto it = kTypes.find(name);
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

struct NrrdHeader {
  std::map<std::string, std::string> fields;  // lower-case key -> trimmed value
  size_t data_offset = 0;                     // first byte after the blank line; npos if none
};

Result<NrrdHeader> parse_nrrd_header(const std::string& bytes, const std::string& path) {
  if (!bytes.starts_with("NRRD000")) {
    return invalid_argument("'" + path + "' is not a NRRD file (it does not start with the NRRD000x magic)");
  }
  NrrdHeader header;
  header.data_offset = std::string::npos;
  size_t pos = bytes.find('\n');
  while (pos != std::string::npos && pos + 1 <= bytes.size()) {
    const size_t start = pos + 1;
    const size_t end = bytes.find('\n', start);
    const std::string_view raw_line(bytes.data() + start, (end == std::string::npos ? bytes.size() : end) - start);
    const std::string_view line = trim(raw_line);
    if (line.empty()) {
      if (end != std::string::npos || start < bytes.size())
        header.data_offset = end == std::string::npos ? bytes.size() : end + 1;
      break;
    }
    pos = end;
    if (line.front() == '#') continue;
    if (line.find(":=") != std::string_view::npos) continue;  // key/value pair: not geometry
    const size_t colon = line.find(": ");
    if (colon == std::string_view::npos) {
      return invalid_argument("NRRD header of '" + path + "' has a malformed line '" + std::string(line.substr(0, 80)) +
                              "' (expected 'field: value')");
    }
    header.fields[to_lower(trim(line.substr(0, colon)))] = std::string(trim(line.substr(colon + 2)));
  }
  return header;
}

Result<std::string> field(const NrrdHeader& h, const std::string& key, const std::string& path) {
  const auto it = h.fields.find(key);
  if (it == h.fields.end()) return invalid_argument("NRRD header of '" + path + "' has no '" + key + "' field");
  return it->second;
}

Status bad_nrrd_field(const std::string& path, const std::string& key, const std::string& value,
                      const std::string& why) {
  return invalid_argument("NRRD header of '" + path + "' has an invalid '" + key + ": " + value.substr(0, 80) + "' (" +
                          why + ")");
}

Result<ImageGeometry> parse_geometry(const NrrdHeader& h, const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(const std::string dimension, field(h, "dimension", path));
  if (parse_integer(dimension) != 3) return bad_nrrd_field(path, "dimension", dimension, "soiq reads 3D images only");
  SOIQ_ASSIGN_OR_RETURN(const std::string sizes_text, field(h, "sizes", path));
  const auto sizes = split_words(sizes_text);
  std::array<int64_t, 3> dims{};
  for (int a = 0; a < 3; ++a) {
    const auto n = a < int(sizes.size()) ? parse_integer(sizes[a]) : std::nullopt;
    if (sizes.size() != 3 || !n || *n < 1)
      return bad_nrrd_field(path, "sizes", sizes_text, "expected 3 positive integers");
    dims[a] = *n;
  }
  Mat3 axes{};
  Vec3 origin{0, 0, 0};
  if (const auto it = h.fields.find("space directions"); it != h.fields.end()) {
    const auto values = parse_doubles(it->second, 9);
    if (!values) return bad_nrrd_field(path, "space directions", it->second, "expected 3 vectors (x,y,z)");
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) axes[r][c] = (*values)[c * 3 + r];
    }
  } else if (const auto sp = h.fields.find("spacings"); sp != h.fields.end()) {
    const auto values = parse_doubles(sp->second, 3);
    if (!values) return bad_nrrd_field(path, "spacings", sp->second, "expected 3 numbers");
    for (int a = 0; a < 3; ++a) axes[a][a] = std::isnan((*values)[a]) ? 1.0 : (*values)[a];
  } else {
    axes = identity3();
  }
  if (const auto it = h.fields.find("space origin"); it != h.fields.end()) {
    const auto values = parse_doubles(it->second, 3);
    if (!values) return bad_nrrd_field(path, "space origin", it->second, "expected (x,y,z)");
    origin = {(*values)[0], (*values)[1], (*values)[2]};
  }
  // Flip the axes the file's space names opposite to LPS.
  std::array<bool, 3> flip{false, false, false};
  if (const auto it = h.fields.find("space"); it != h.fields.end()) {
    const std::string space = to_lower(it->second);
    if (space == "right-anterior-superior" || space == "ras") {
      flip = {true, true, false};
    } else if (space == "left-anterior-superior" || space == "las") {
      flip = {false, true, false};
    } else if (space != "left-posterior-superior" && space != "lps") {
      return bad_nrrd_field(path, "space", it->second, "soiq reads LPS, RAS and LAS spaces");
    }
  }
  for (int r = 0; r < 3; ++r) {
    if (!flip[r]) continue;
    origin[r] = -origin[r];
    for (int c = 0; c < 3; ++c) axes[r][c] = -axes[r][c];
  }
  return geometry_from_axes(axes, origin, dims, path);
}

// The encoded voxel bytes: the attached data after the header, or the detached data file when
// the header's own directory is known (a local file); bytes from elsewhere cannot name a file.
Result<std::string> data_bytes(const std::string& bytes, const NrrdHeader& h, const std::string& path,
                               const std::optional<std::string>& detached_dir) {
  auto it = h.fields.find("data file");
  if (it == h.fields.end()) it = h.fields.find("datafile");
  if (it == h.fields.end()) {
    if (h.data_offset == std::string::npos) {
      return invalid_argument("NRRD '" + path + "' has no blank line ending its header, so no attached data");
    }
    return bytes.substr(h.data_offset);
  }
  const std::string& name = it->second;
  if (!detached_dir) {
    return invalid_argument("NRRD '" + path + "' names a separate data file ('data file: " + name.substr(0, 80) +
                            "'); soiq reads uploaded images only with their data attached: save it as one .nrrd");
  }
  if (name.starts_with("LIST") || name.find('%') != std::string::npos || split_words(name).size() != 1) {
    return bad_nrrd_field(path, "data file", name, "multi-file data is not supported");
  }
  const std::string data_path = name.starts_with("/") ? name : *detached_dir + name;
  return read_file_bytes(data_path, "NRRD data");
}

}  // namespace

Result<Image> read_nrrd(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(const std::string bytes, read_file_bytes(path, "image"));
  return parse_nrrd(bytes, path, directory_of(path), {});
}

Result<Image> parse_nrrd(const std::string& bytes, const std::string& path,
                         const std::optional<std::string>& detached_dir, const ImageDecodeLimits& limits) {
  if (bytes.empty()) return invalid_argument("image file '" + path + "' is empty");
  SOIQ_ASSIGN_OR_RETURN(const NrrdHeader header, parse_nrrd_header(bytes, path));
  SOIQ_ASSIGN_OR_RETURN(const std::string type_name, field(header, "type", path));
  const auto type = nrrd_voxel_type(to_lower(type_name));
  if (!type) return bad_nrrd_field(path, "type", type_name, "soiq reads 8-32 bit integers, float and double");
  SOIQ_ASSIGN_OR_RETURN(const ImageGeometry geometry, parse_geometry(header, path));
  Image image{geometry, {}};
  SOIQ_RETURN_IF_ERROR(check_before_decoding(image.geometry, voxel_type_size(*type), limits));
  const size_t count = size_t(image.geometry.voxel_count());
  const size_t needed = count * voxel_type_size(*type);

  SOIQ_ASSIGN_OR_RETURN(const std::string encoding_text, field(header, "encoding", path));
  const std::string encoding = to_lower(encoding_text);
  bool swap = false;
  if (voxel_type_size(*type) > 1 && encoding != "ascii" && encoding != "text" && encoding != "txt") {
    SOIQ_ASSIGN_OR_RETURN(const std::string endian, field(header, "endian", path));
    if (endian != "little" && endian != "big") return bad_nrrd_field(path, "endian", endian, "expected little or big");
    swap = (endian == "big") != (std::endian::native == std::endian::big);
  }
  long long byte_skip = 0;
  if (const auto it = header.fields.find("byte skip"); it != header.fields.end()) {
    const auto n = parse_integer(it->second);
    if (!n || *n < -1 || (*n != 0 && encoding != "raw")) {
      return bad_nrrd_field(path, "byte skip", it->second, "soiq supports byte skip >= 0 or -1 with raw encoding");
    }
    byte_skip = *n;
  }
  SOIQ_ASSIGN_OR_RETURN(std::string encoded, data_bytes(bytes, header, path, detached_dir));

  if (encoding == "ascii" || encoding == "text" || encoding == "txt") {
    const auto words = split_words(encoded);
    if (words.size() < count) {
      return invalid_argument("NRRD '" + path + "' is truncated: " + std::to_string(words.size()) +
                              " ascii values, expected " + std::to_string(count));
    }
    image.voxels.resize(count);
    for (size_t n = 0; n < count; ++n) {
      const auto v = parse_double(words[n]);
      if (!v)
        return invalid_argument("NRRD '" + path + "' has a malformed ascii value '" + std::string(words[n]) + "'");
      image.voxels[n] = float(*v);
    }
    return image;
  }
  std::string raw;
  if (encoding == "raw") {
    raw = std::move(encoded);
  } else if (encoding == "gzip" || encoding == "gz") {
    SOIQ_ASSIGN_OR_RETURN(raw, inflate_bytes(encoded, needed, path));
  } else {
    return bad_nrrd_field(path, "encoding", encoding_text, "soiq reads raw, gzip and ascii");
  }
  const size_t skip = byte_skip == -1 ? (raw.size() >= needed ? raw.size() - needed : 0) : size_t(byte_skip);
  if (raw.size() < skip || raw.size() - skip < needed) {
    return invalid_argument("NRRD '" + path +
                            "' is truncated: " + std::to_string(raw.size() > skip ? raw.size() - skip : 0) +
                            " bytes of voxel data, expected " + std::to_string(needed));
  }
  image.voxels = decode_voxels(raw.data() + skip, count, *type, swap);
  return image;
}

}  // namespace soiq
