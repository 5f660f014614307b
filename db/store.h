#pragma once
// The Store: everything soiqd keeps (docs/DESIGN.md "Storage"), in three roles, each a narrow
// interface of its own, so that code needing one role takes only it and a backend is read role by
// role (tests/db/ holds each to its contract on both backends):
//   RecordStore   records and their searches, blobs, stage 1 (db/record_store.h)
//   FeatureStore  the feature cache and the precompute queue   (db/feature_store.h)
//   ReplicaStore  the stage-2 work queue replicas share         (db/replica_store.h)
// The SQLite file of one machine and a shared PostgreSQL database implement all three on the same
// SQL (db/sql/). Records are plain structs; blobs are already encoded (db/surface_blob.h,
// db/image_blob.h).
//
// Contract for every implementation
//   - Every method that writes does so in one transaction: on error nothing of it is kept; on
//     success it is durable (a killed server loses nothing that was acknowledged).
//   - Errors are soiq::Status codes: NOT_FOUND for an unknown id (the message names it),
//     INVALID_ARGUMENT for a bad filter or page token, DATA_LOSS for a corrupt record, UNAVAILABLE
//     when the database is busy past its timeout, INTERNAL otherwise.
//   - Safe to call from many threads at once.

#include "db/feature_store.h"
#include "db/record_store.h"
#include "db/replica_store.h"

namespace soiq::db {

class Store : public RecordStore, public FeatureStore, public ReplicaStore {};

}  // namespace soiq::db
