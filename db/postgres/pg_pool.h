#pragma once
// A fixed set of PostgreSQL connections shared by a soiqd's threads (soiqd --db-connections N):
// a thread leases one for a statement or a transaction and gives it back when the lease ends. The
// pool bounds what one replica asks of the server; a lease waits, bounded, when all are out.
//
// open      connects all `size` connections at once (a wrong address fails at start, not at the
//           first query) and brings the schema up to date on the first (pg_schema.h); read only,
//           leaves the schema as it is (pg_check_schema_readable) and makes every transaction
//           of the connections read only, so PostgreSQL itself refuses any write.
// acquire   a free connection, waiting up to `wait`; DEADLINE_EXCEEDED naming the pool's size
//           when none came free. A connection found broken when leased is reset first; UNAVAILABLE
//           when that fails (the server is down).
// Thread-safe.

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/postgres/pg_connection.h"

namespace soiq::db {

class PgPool {
 public:
  class Lease {
   public:
    Lease(PgPool* pool, size_t slot) : pool_(pool), slot_(slot) {}
    Lease(Lease&& o) noexcept : pool_(o.pool_), slot_(o.slot_) { o.pool_ = nullptr; }
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    Lease& operator=(Lease&&) = delete;
    ~Lease() {
      if (pool_ != nullptr) pool_->release(slot_);
    }
    PgConnection& operator*() const { return pool_->connections_[slot_]; }
    PgConnection* operator->() const { return &pool_->connections_[slot_]; }

   private:
    PgPool* pool_;
    size_t slot_;
  };

  static Result<std::unique_ptr<PgPool>> open(const std::string& conninfo, int size, bool read_only = false);

  Result<Lease> acquire(std::chrono::milliseconds wait);
  int size() const { return int(connections_.size()); }

 private:
  PgPool() = default;
  void release(size_t slot);

  std::vector<PgConnection> connections_;
  std::mutex mutex_;
  std::condition_variable freed_;
  std::vector<size_t> free_;  // slots not leased
};

}  // namespace soiq::db
