#include "bench/orthanc_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "dicom/pacs_echo.h"
#include "tests/support/dcmqrscp_process.h"

namespace soiq::bench {

std::string OrthancProcess::start(bool dicomweb) {
  const std::string binary = "/usr/sbin/Orthanc";
  if (::access(binary.c_str(), X_OK) != 0)
    return "not installed: /usr/sbin/Orthanc (Debian package orthanc; scripts/install-deps)";
  std::string plugin;
  if (dicomweb) {
    for (const char* p : {"/usr/lib/orthanc/libOrthancDicomWeb.so.1.7", "/usr/lib/orthanc/libOrthancDicomWeb.so"})
      if (plugin.empty() && ::access(p, R_OK) == 0) plugin = p;
    if (plugin.empty()) return "not installed: Orthanc's DICOMweb plugin (Debian package orthanc-dicomweb)";
    http_port_ = dicom::testing::free_loopback_port();
  }
  const std::string storage = (dir_.path() / "storage").string();
  port_ = dicom::testing::free_loopback_port();
  const std::string config = (dir_.path() / "orthanc.json").string();
  std::ofstream(config) << "{\n"
                        << "  \"Name\": \"soiq-bench\",\n"
                        << "  \"StorageDirectory\": \"" << storage << "\",\n"
                        << "  \"IndexDirectory\": \"" << storage << "\",\n"
                        << "  \"HttpServerEnabled\": " << (dicomweb ? "true" : "false") << ",\n"
                        << "  \"HttpPort\": " << (dicomweb ? http_port_ : 8042) << ",\n"
                        << "  \"RemoteAccessAllowed\": false,\n"
                        << "  \"AuthenticationEnabled\": false,\n"
                        << "  \"DicomWeb\": { \"Enable\": true, \"Root\": \"/dicom-web/\" },\n"
                        << "  \"DicomServerEnabled\": true,\n"
                        << "  \"DicomAet\": \"" << kAeTitle << "\",\n"
                        << "  \"DicomPort\": " << port_ << ",\n"
                        << "  \"DicomCheckCalledAet\": false,\n"
                        << "  \"DicomAlwaysAllowEcho\": true,\n"
                        << "  \"DicomAlwaysAllowStore\": true,\n"
                        << "  \"DicomAlwaysAllowFind\": true,\n"
                        << "  \"DicomAlwaysAllowGet\": true,\n"
                        << "  \"Plugins\": [" << (plugin.empty() ? "" : "\"" + plugin + "\"") << "],\n"
                        << "  \"SaveJobs\": false\n"
                        << "}\n";
  pid_ = ::fork();
  if (pid_ < 0) return "fork failed";
  if (pid_ == 0) {
    ::setpgid(0, 0);
    const int fd = ::open((dir_.path() / "orthanc.log").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
    }
    ::execl(binary.c_str(), binary.c_str(), config.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid_, pid_);
  dicom::PacsPeer probe = peer();
  probe.timeout_seconds = 2;
  for (int i = 0; i < 500; ++i) {  // 10 s
    if (dicom::pacs_echo(probe).ok()) return "";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  stop();
  return "Orthanc did not answer C-ECHO on port " + std::to_string(port_) + ":\n" +
         dicom::testing::read_text(dir_.path() / "orthanc.log");
}

void OrthancProcess::stop() { dicom::testing::stop_process_group(pid_, std::chrono::seconds(5)); }

dicom::PacsPeer OrthancProcess::peer() const {
  dicom::PacsPeer p;
  p.called_ae = kAeTitle;
  p.host = "127.0.0.1";
  p.port = port_;
  p.calling_ae = "SOIQ";
  p.timeout_seconds = 30;
  return p;
}

}  // namespace soiq::bench
