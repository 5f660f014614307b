#include "core/io/vtk_messages.h"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <mutex>
#include <string_view>

namespace soiq {
namespace {

struct ThreadMessages {
  bool has_error = false;
  std::string last_error;
  std::string last_warning;
};

thread_local ThreadMessages t_messages;

// VTK 9.1 creates its object-factory registry lazily, on the first factory-made object (vtkPoints,
// readers, ...), without a lock: two threads making their first VTK objects at once each create
// one, and one leaks. Every program that links soiq's VTK adapters creates it here, at load time,
// while only one thread exists, so no code path has to remember to do it first.
[[maybe_unused]] const bool kVtkFactoryRegistryCreated = (vtkObjectFactory::GetRegisteredFactories(), true);

// "ERROR: In /path/vtkSTLReader.cxx, line 123\nvtkSTLReader (0x55d): File x not found\n\n"
// -> "File x not found"
std::string strip_vtk_prefix(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.remove_suffix(1);
  const size_t newline = text.find('\n');
  if (text.starts_with("ERROR: In ") || text.starts_with("Warning: In ")) {
    if (newline != std::string_view::npos) text.remove_prefix(newline + 1);
  }
  const size_t object = text.find("): ");
  if (object != std::string_view::npos && text.find(" (0x") != std::string_view::npos && object < 200) {
    text.remove_prefix(object + 3);
  }
  return std::string(text);
}

class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow);

  void DisplayText(const char* text) override {
    if (text == nullptr) return;
    switch (this->GetCurrentMessageType()) {
      case MESSAGE_TYPE_ERROR:
        t_messages.has_error = true;
        t_messages.last_error = strip_vtk_prefix(text);
        break;
      case MESSAGE_TYPE_WARNING:
      case MESSAGE_TYPE_GENERIC_WARNING:
        t_messages.last_warning = strip_vtk_prefix(text);
        break;
      default:
        break;
    }
  }

 protected:
  CapturingOutputWindow() { this->PromptUserOff(); }
};

vtkStandardNewMacro(CapturingOutputWindow);

}  // namespace

VtkMessages::VtkMessages() {
  static std::once_flag installed;
  std::call_once(installed, [] {
    vtkSmartPointer<CapturingOutputWindow> window = vtkSmartPointer<CapturingOutputWindow>::New();
    vtkOutputWindow::SetInstance(window);
    // VTK 9 also logs every error through vtkLogger straight to stderr.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  });
  t_messages = ThreadMessages{};
}

bool VtkMessages::has_error() const { return t_messages.has_error; }

std::string VtkMessages::last_error() const {
  return t_messages.last_error.empty() ? t_messages.last_warning : t_messages.last_error;
}

}  // namespace soiq
