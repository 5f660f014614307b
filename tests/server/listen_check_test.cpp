#include "server/util/listen_check.h"

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>

namespace soiq::server {
namespace {

// A loopback socket that listens on a port the kernel chose, closed on destruction.
class Listener {
 public:
  Listener() {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&a), len) != 0 || ::listen(fd_, 1) != 0 ||
        ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
      return;
    }
    port_ = ntohs(a.sin_port);
  }
  ~Listener() {
    if (fd_ >= 0) ::close(fd_);
  }
  int port() const { return port_; }

 private:
  int fd_ = -1;
  int port_ = 0;
};

TEST(WhyCannotListen, APortAnotherProcessListensOnIsInUseAndAsksForAnotherSoiqd) {
  Listener taken;
  ASSERT_GT(taken.port(), 0);
  const std::string address = "127.0.0.1:" + std::to_string(taken.port());
  const std::string why = why_cannot_listen(address);
  EXPECT_NE(why.find(address + " is already in use"), std::string::npos) << why;
  EXPECT_NE(why.find("another soiqd"), std::string::npos) << why;
}

TEST(WhyCannotListen, AFreePortHasNoReason) {
  int port = 0;
  {
    Listener released;
    port = released.port();
  }
  ASSERT_GT(port, 0);
  EXPECT_EQ(why_cannot_listen("127.0.0.1:" + std::to_string(port)), "");
}

TEST(WhyCannotListen, AnAddressOfAnotherMachineIsNamed) {
  // 192.0.2.0/24 is TEST-NET-1 (RFC 5737): never an address of this machine.
  const std::string why = why_cannot_listen("192.0.2.1:50051");
  EXPECT_NE(why.find("192.0.2.1 is not an address of this machine"), std::string::npos) << why;
}

TEST(WhyCannotListen, TextWithoutAPortIsNamed) {
  EXPECT_NE(why_cannot_listen("localhost").find("'localhost' is not HOST:PORT"), std::string::npos);
}

}  // namespace
}  // namespace soiq::server
