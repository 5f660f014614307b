#pragma once
// Captures what VTK would print to stderr. VTK's readers and writers report errors through the
// global vtkOutputWindow and often still return (empty) output; soiq needs those messages in its
// Status instead. The first VtkMessages ever constructed installs a process-wide output window
// that prints nothing and appends every message to a per-thread buffer; each VtkMessages clears
// that buffer, so `last_error()` sees only the messages of the VTK calls made since on this thread.
//
// Linking this file also creates VTK's object-factory registry at program load (VTK 9.1 creates
// it lazily and without a lock, so threads making their first VTK objects at once raced there).
//
// Usage    VtkMessages messages; reader->Update(); if (messages.has_error()) ...
// Cost     O(1). Thread-safe: installation is guarded, buffers are thread-local.
// Caveats  Replaces vtkOutputWindow and turns vtkLogger's stderr output off for the whole process:
//          VTK never prints to stderr afterwards.

#include <string>

namespace soiq {

class VtkMessages {
 public:
  VtkMessages();
  VtkMessages(const VtkMessages&) = delete;
  VtkMessages& operator=(const VtkMessages&) = delete;

  // True when VTK reported an error (not a warning) on this thread since construction.
  bool has_error() const;
  // The text of the last error (or, failing that, the last warning), without VTK's
  // "ERROR: In file.cxx, line N / vtkClass (0x...):" prefix; "" when there was none.
  std::string last_error() const;
};

}  // namespace soiq
