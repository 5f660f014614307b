#include "core/io/voxel_type.h"

#include <algorithm>
#include <cstring>

namespace soiq {
namespace {

template <typename T>
void decode_as(const char* bytes, size_t count, bool swap_bytes, std::vector<float>& out) {
  char tmp[sizeof(T)];
  for (size_t n = 0; n < count; ++n) {
    std::memcpy(tmp, bytes + n * sizeof(T), sizeof(T));
    if (swap_bytes) std::reverse(tmp, tmp + sizeof(T));
    T value;
    std::memcpy(&value, tmp, sizeof(T));
    out[n] = static_cast<float>(value);
  }
}

}  // namespace

size_t voxel_type_size(VoxelType type) {
  switch (type) {
    case VoxelType::kUint8:
    case VoxelType::kInt8:
      return 1;
    case VoxelType::kUint16:
    case VoxelType::kInt16:
      return 2;
    case VoxelType::kUint32:
    case VoxelType::kInt32:
    case VoxelType::kFloat32:
      return 4;
    case VoxelType::kFloat64:
      return 8;
  }
  return 1;
}

std::vector<float> decode_voxels(const char* bytes, size_t count, VoxelType type, bool swap_bytes) {
  std::vector<float> out(count);
  switch (type) {
    case VoxelType::kUint8:
      decode_as<uint8_t>(bytes, count, false, out);
      break;
    case VoxelType::kInt8:
      decode_as<int8_t>(bytes, count, false, out);
      break;
    case VoxelType::kUint16:
      decode_as<uint16_t>(bytes, count, swap_bytes, out);
      break;
    case VoxelType::kInt16:
      decode_as<int16_t>(bytes, count, swap_bytes, out);
      break;
    case VoxelType::kUint32:
      decode_as<uint32_t>(bytes, count, swap_bytes, out);
      break;
    case VoxelType::kInt32:
      decode_as<int32_t>(bytes, count, swap_bytes, out);
      break;
    case VoxelType::kFloat32:
      decode_as<float>(bytes, count, swap_bytes, out);
      break;
    case VoxelType::kFloat64:
      decode_as<double>(bytes, count, swap_bytes, out);
      break;
  }
  return out;
}

}  // namespace soiq
