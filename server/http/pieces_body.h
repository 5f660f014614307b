#pragma once
// A Boost.Beast body type for answers made of pieces (HttpReply's body, then its pieces, as
// http_reply.h holds them): the serializer writes each piece where it lies, so a large answer
// (the SEGs of a study) is never gathered into one more buffer.

#include <boost/asio/buffer.hpp>
#include <boost/beast/core/error.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/optional.hpp>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace soiq::server::http {

struct PiecesBody {
  using value_type = std::vector<std::string>;
  static std::uint64_t size(const value_type& v) {
    std::uint64_t n = 0;
    for (const std::string& p : v) n += p.size();
    return n;
  }
  class writer {
   public:
    using const_buffers_type = boost::asio::const_buffer;
    template <bool isRequest, class Fields>
    writer(const boost::beast::http::header<isRequest, Fields>&, const value_type& v) : v_(v) {}
    void init(boost::beast::error_code& ec) { ec = {}; }
    boost::optional<std::pair<const_buffers_type, bool>> get(boost::beast::error_code& ec) {
      ec = {};
      while (next_ < v_.size() && v_[next_].empty()) ++next_;
      if (next_ == v_.size()) return boost::none;
      const std::string& piece = v_[next_++];
      bool more = false;
      for (size_t i = next_; i < v_.size() && !more; ++i) more = !v_[i].empty();
      return std::make_pair(boost::asio::const_buffer(piece.data(), piece.size()), more);
    }

   private:
    const value_type& v_;
    size_t next_ = 0;
  };
};

}  // namespace soiq::server::http
