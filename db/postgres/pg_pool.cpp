#include "db/postgres/pg_pool.h"

#include "db/postgres/pg_schema.h"

namespace soiq::db {

Result<std::unique_ptr<PgPool>> PgPool::open(const std::string& conninfo, int size, bool read_only) {
  if (size < 1 || size > 1000) {
    return invalid_argument("PostgreSQL connection pool size must be 1 to 1000, got " + std::to_string(size));
  }
  std::unique_ptr<PgPool> pool(new PgPool);
  pool->connections_.reserve(size_t(size));
  for (int i = 0; i < size; ++i) {
    SOIQ_ASSIGN_OR_RETURN(PgConnection c, PgConnection::open(conninfo));
    if (read_only) {
      SOIQ_RETURN_IF_ERROR(c.run("SET default_transaction_read_only = on", "open the connection for reading only"));
    }
    pool->connections_.push_back(std::move(c));
    pool->free_.push_back(size_t(i));
  }
  SOIQ_RETURN_IF_ERROR(read_only ? pg_check_schema_readable(pool->connections_[0]) : pg_migrate(pool->connections_[0]));
  return pool;
}

Result<PgPool::Lease> PgPool::acquire(std::chrono::milliseconds wait) {
  size_t slot = 0;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!freed_.wait_for(lock, wait, [&] { return !free_.empty(); })) {
      return Status(StatusCode::kDeadlineExceeded, "all " + std::to_string(connections_.size()) +
                                                       " PostgreSQL connections stayed busy for " +
                                                       std::to_string(wait.count()) + " ms");
    }
    slot = free_.back();
    free_.pop_back();
  }
  Lease lease(this, slot);  // from here on the slot goes back whatever happens
  if (!connections_[slot].healthy() && !connections_[slot].reset()) {
    return Status(StatusCode::kUnavailable, "the PostgreSQL connection was lost and cannot be made again");
  }
  return lease;
}

void PgPool::release(size_t slot) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(slot);
  }
  freed_.notify_one();
}

}  // namespace soiq::db
