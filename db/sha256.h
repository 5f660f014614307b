#pragma once
// Incremental sha256 (OpenSSL EVP) for content hashes of stored blobs, as lower-case hex.
// sha256_hex() of surface_blob.h is the one-shot form.

#include <cstddef>
#include <memory>
#include <string>

struct evp_md_ctx_st;

namespace soiq::db {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void update(const void* data, size_t size);
  // 64 lower-case hex digits; the hasher is finished afterwards.
  std::string hex_digest();

 private:
  evp_md_ctx_st* ctx_;
};

}  // namespace soiq::db
