#include "core/io/read_metaimage.h"

#include <algorithm>
#include <bit>
#include <map>
#include <optional>

#include "core/io/geometry_from_axes.h"
#include "core/io/header_text.h"
#include "core/io/read_file_bytes.h"
#include "core/io/voxel_type.h"
#include "core/io/zlib_codec.h"

namespace soiq {
namespace {

std::optional<VoxelType> met_voxel_type(const std::string& name) {
  static const std::map<std::string, VoxelType> kTypes = {
      {"MET_UCHAR", VoxelType::kUint8},   {"MET_CHAR", VoxelType::kInt8},     {"MET_USHORT", VoxelType::kUint16},
      {"MET_SHORT", VoxelType::kInt16},   {"MET_UINT", VoxelType::kUint32},   {"MET_INT", VoxelType::kInt32},
      {"MET_FLOAT", VoxelType::kFloat32}, {"MET_DOUBLE", VoxelType::kFloat64}};
  const auto it = kTypes.find(name);
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

struct MetaHeader {
  std::map<std::string, std::string> fields;  // key as written (MetaIO keys are case-sensitive)
  size_t data_offset = 0;                     // first byte after the ElementDataFile line
};

Result<MetaHeader> parse_meta_header(const std::string& bytes, const std::string& path) {
  MetaHeader header;
  size_t start = 0;
  while (start < bytes.size()) {
    size_t end = bytes.find('\n', start);
    if (end == std::string::npos) end = bytes.size();
    const std::string_view line = trim(std::string_view(bytes).substr(start, end - start));
    start = end + 1;
    if (line.empty()) continue;
    const size_t eq = line.find('=');
    if (eq == std::string_view::npos) {
      return invalid_argument("MetaImage header of '" + path + "' has a malformed line '" +
                              std::string(line.substr(0, 80)) + "' (expected 'Key = Value')");
    }
    const std::string key(trim(line.substr(0, eq)));
    header.fields[key] = std::string(trim(line.substr(eq + 1)));
    // ElementDataFile is always the last field; binary data may follow it directly.
    if (key == "ElementDataFile") {
      header.data_offset = std::min(start, bytes.size());
      return header;
    }
  }
  return invalid_argument("MetaImage header of '" + path + "' has no ElementDataFile field");
}

const std::string* find_first(const MetaHeader& h, std::initializer_list<const char*> keys) {
  for (const char* key : keys) {
    if (const auto it = h.fields.find(key); it != h.fields.end()) return &it->second;
  }
  return nullptr;
}

Status bad_meta_field(const std::string& path, const std::string& key, const std::string& value,
                      const std::string& why) {
  return invalid_argument("MetaImage header of '" + path + "' has an invalid '" + key + " = " + value.substr(0, 80) +
                          "' (" + why + ")");
}

bool is_true(const std::string* value) { return value && to_lower(*value) == "true"; }

Result<ImageGeometry> parse_geometry(const MetaHeader& h, const std::string& path) {
  const std::string* ndims = find_first(h, {"NDims"});
  if (!ndims) return invalid_argument("MetaImage header of '" + path + "' has no NDims field");
  if (parse_integer(*ndims) != 3) return bad_meta_field(path, "NDims", *ndims, "soiq reads 3D images only");
  const std::string* dim_size = find_first(h, {"DimSize"});
  if (!dim_size) return invalid_argument("MetaImage header of '" + path + "' has no DimSize field");
  const auto sizes = split_words(*dim_size);
  std::array<int64_t, 3> dims{};
  for (int a = 0; a < 3; ++a) {
    const auto n = a < int(sizes.size()) ? parse_integer(sizes[a]) : std::nullopt;
    if (sizes.size() != 3 || !n || *n < 1)
      return bad_meta_field(path, "DimSize", *dim_size, "expected 3 positive integers");
    dims[a] = *n;
  }
  Vec3 spacing{1, 1, 1};
  if (const std::string* s = find_first(h, {"ElementSpacing", "ElementSize"})) {
    const auto v = parse_doubles(*s, 3);
    if (!v) return bad_meta_field(path, "ElementSpacing", *s, "expected 3 numbers");
    spacing = {(*v)[0], (*v)[1], (*v)[2]};
    if (!(spacing[0] > 0 && spacing[1] > 0 && spacing[2] > 0))
      return bad_meta_field(path, "ElementSpacing", *s, "must be > 0");
  }
  Vec3 origin{0, 0, 0};
  if (const std::string* s = find_first(h, {"Offset", "Position", "Origin"})) {
    const auto v = parse_doubles(*s, 3);
    if (!v) return bad_meta_field(path, "Offset", *s, "expected 3 numbers");
    origin = {(*v)[0], (*v)[1], (*v)[2]};
  }
  Mat3 direction = identity3();
  if (const std::string* s = find_first(h, {"TransformMatrix", "Rotation", "Orientation"})) {
    const auto v = parse_doubles(*s, 9);
    if (!v) return bad_meta_field(path, "TransformMatrix", *s, "expected 9 numbers");
    // Consecutive triples are the axis directions, i.e. the columns of D.
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) direction[r][c] = (*v)[c * 3 + r];
    }
  }
  Mat3 axes{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) axes[r][c] = direction[r][c] * spacing[c];
  }
  return geometry_from_axes(axes, origin, dims, path);
}

}  // namespace

Result<Image> read_metaimage(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(const std::string bytes, read_file_bytes(path, "image"));
  return parse_metaimage(bytes, path, directory_of(path), {});
}

Result<Image> parse_metaimage(const std::string& bytes, const std::string& path,
                              const std::optional<std::string>& detached_dir, const ImageDecodeLimits& limits) {
  if (bytes.empty()) return invalid_argument("image file '" + path + "' is empty");
  SOIQ_ASSIGN_OR_RETURN(const MetaHeader header, parse_meta_header(bytes, path));
  if (const std::string* object = find_first(header, {"ObjectType"}); object && *object != "Image") {
    return bad_meta_field(path, "ObjectType", *object, "expected Image");
  }
  if (const std::string* channels = find_first(header, {"ElementNumberOfChannels"});
      channels && parse_integer(*channels) != 1) {
    return bad_meta_field(path, "ElementNumberOfChannels", *channels, "soiq reads single-channel images only");
  }
  const std::string* type_name = find_first(header, {"ElementType"});
  if (!type_name) return invalid_argument("MetaImage header of '" + path + "' has no ElementType field");
  const auto type = met_voxel_type(*type_name);
  if (!type)
    return bad_meta_field(path, "ElementType", *type_name, "soiq reads MET_UCHAR..MET_INT, MET_FLOAT, MET_DOUBLE");
  SOIQ_ASSIGN_OR_RETURN(const ImageGeometry geometry, parse_geometry(header, path));
  SOIQ_RETURN_IF_ERROR(check_before_decoding(geometry, voxel_type_size(*type), limits));
  const size_t count = size_t(geometry.voxel_count());
  const size_t needed = count * voxel_type_size(*type);

  const std::string& data_file = header.fields.at("ElementDataFile");
  std::string encoded;
  if (data_file == "LOCAL") {
    encoded = bytes.substr(header.data_offset);
  } else {
    if (!detached_dir) {
      return invalid_argument("MetaImage '" + path +
                              "' names a separate data file ('ElementDataFile = " + data_file.substr(0, 80) +
                              "'); soiq reads uploaded images only with their data attached: save it as one .mha "
                              "(ElementDataFile = LOCAL)");
    }
    if (data_file.starts_with("LIST") || data_file.find('%') != std::string::npos ||
        split_words(data_file).size() != 1) {
      return bad_meta_field(path, "ElementDataFile", data_file, "multi-file data is not supported");
    }
    const std::string data_path = data_file.starts_with("/") ? data_file : *detached_dir + data_file;
    SOIQ_ASSIGN_OR_RETURN(encoded, read_file_bytes(data_path, "MetaImage data"));
  }
  const bool big_endian = is_true(find_first(header, {"BinaryDataByteOrderMSB", "ElementByteOrderMSB"}));
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  std::string raw;
  if (is_true(find_first(header, {"CompressedData"}))) {
    SOIQ_ASSIGN_OR_RETURN(raw, inflate_bytes(encoded, needed, path));
  } else {
    raw = std::move(encoded);
    if (const std::string* hs = find_first(header, {"HeaderSize"}); hs && data_file != "LOCAL") {
      const auto n = parse_integer(*hs);
      if (!n || *n < -1) return bad_meta_field(path, "HeaderSize", *hs, "expected an integer >= -1");
      const size_t skip = *n == -1 ? (raw.size() >= needed ? raw.size() - needed : 0) : size_t(*n);
      raw.erase(0, std::min(skip, raw.size()));
    }
  }
  if (raw.size() < needed) {
    return invalid_argument("MetaImage '" + path + "' is truncated: " + std::to_string(raw.size()) +
                            " bytes of voxel data, expected " + std::to_string(needed));
  }
  return Image{geometry, decode_voxels(raw.data(), count, *type, swap)};
}

}  // namespace soiq
