#pragma once
// VTK's PLY reader and writer (vtkPLY) keep state in static variables, so two threads reading or
// writing PLY files at once corrupt the heap ("free(): invalid size", seen with soiq-bench query's
// parallel cohort writer). Every PLY read and write in soiq holds this lock; other formats do not.

#include <mutex>

namespace soiq {

inline std::mutex& vtk_ply_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace soiq
