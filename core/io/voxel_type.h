#pragma once
// The scalar types soiq reads from image files, and their conversion to float voxels.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace soiq {

enum class VoxelType { kUint8, kInt8, kUint16, kInt16, kUint32, kInt32, kFloat32, kFloat64 };

// Bytes per voxel: 1, 1, 2, 2, 4, 4, 4, 8.
size_t voxel_type_size(VoxelType type);

// Converts `count` voxels of `type` starting at `bytes` to float. `swap_bytes` when the file's byte
// order differs from the machine's. `bytes` needs count * voxel_type_size(type) readable bytes;
// no alignment is assumed. 32-bit integers and doubles lose precision beyond float's 24 bits.
// Cost O(count); thread-safe.
std::vector<float> decode_voxels(const char* bytes, size_t count, VoxelType type, bool swap_bytes);

}  // namespace soiq
