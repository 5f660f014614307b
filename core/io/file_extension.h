#pragma once
// The lower-case extension of a file name, including the leading dot, with the double extension
// ".nii.gz" kept whole: "a/B.STL" -> ".stl", "x.nii.gz" -> ".nii.gz", "noext" -> "".
// Pure string work; thread-safe.

#include <string>

namespace soiq {

std::string file_extension(const std::string& path);

}  // namespace soiq
