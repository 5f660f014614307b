#include "db/sqlite/schema_reencode.h"

#include <string>
#include <vector>

#include "db/image_blob.h"
#include "db/sql/checksum_stored_bytes.h"
#include "db/sqlite/sqlite_session.h"
#include "db/sqlite/sqlite_statement.h"
#include "db/surface_blob.h"

namespace soiq::db {

Status reencode_surface_blobs(Connection& c) {
  std::vector<std::string> shas;
  {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare("SELECT sha256 FROM surfaces"));
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      shas.push_back(q.text(0));
    }
  }
  SOIQ_ASSIGN_OR_RETURN(Statement read, c.prepare("SELECT blob FROM surfaces WHERE sha256 = ?"));
  SOIQ_ASSIGN_OR_RETURN(Statement write_blob, c.prepare("UPDATE surfaces SET blob = ? WHERE sha256 = ?"));
  SOIQ_ASSIGN_OR_RETURN(
      Statement write_measure,
      c.prepare(
          "UPDATE structures SET surface_area_bound_mm2 = ?, surface_perimeter_bound_mm = ? WHERE surface_sha256 = ?"));
  for (const std::string& sha : shas) {
    read.reset();
    read.bind(1, sha);
    SOIQ_ASSIGN_OR_RETURN(const bool found, read.step());
    if (!found) continue;
    const std::string blob = read.blob(0);
    Result<TriangleMesh> mesh = decode_surface(blob);
    if (!mesh.ok()) return Status(mesh.status().code(), "surface " + sha + ": " + mesh.status().message());
    SOIQ_ASSIGN_OR_RETURN(const EncodedSurface encoded, encode_surface(*mesh));
    if (is_deflated_surface_blob(blob)) {
      write_blob.reset();
      write_blob.bind_blob(1, encoded.blob.data(), encoded.blob.size());
      write_blob.bind(2, sha);
      SOIQ_RETURN_IF_ERROR(write_blob.step().status());
    }
    write_measure.reset();
    write_measure.bind(1, encoded.info.area_bound_mm2);
    write_measure.bind(2, encoded.info.perimeter_bound_mm);
    write_measure.bind(3, sha);
    SOIQ_RETURN_IF_ERROR(write_measure.step().status());
  }
  return ok_status();
}

// Version 5's step SQL cannot say: each image blob of version 1 (zlib) in the delta-planes codec of
// image_blob.h, which a cold query decodes several times faster. The sha256 is over the voxels and
// the geometry, not the codec, and stays; the geometry comes from a series that holds the image.
Status reencode_image_blobs(Connection& c) {
  std::vector<std::string> shas;
  {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare("SELECT sha256 FROM image_blobs"));
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      shas.push_back(q.text(0));
    }
  }
  SOIQ_ASSIGN_OR_RETURN(Statement read, c.prepare(R"sql(
    SELECT b.blob, se.origin_x, se.origin_y, se.origin_z, se.spacing_x, se.spacing_y, se.spacing_z,
           se.dim_x, se.dim_y, se.dim_z, se.d00, se.d01, se.d02, se.d10, se.d11, se.d12, se.d20, se.d21, se.d22
    FROM image_blobs b JOIN series se ON se.image_sha256 = b.sha256
    WHERE b.sha256 = ? LIMIT 1)sql"));
  SOIQ_ASSIGN_OR_RETURN(Statement write, c.prepare("UPDATE image_blobs SET blob = ? WHERE sha256 = ?"));
  for (const std::string& sha : shas) {
    read.reset();
    read.bind(1, sha);
    SOIQ_ASSIGN_OR_RETURN(const bool found, read.step());
    if (!found) continue;  // no series holds it: nothing will read it
    const std::string blob = read.blob(0);
    if (!is_deflated_image_blob(blob)) continue;
    ImageGeometry g;
    for (int a = 0; a < 3; ++a) {
      g.origin_mm[a] = read.real(1 + a);
      g.spacing_mm[a] = read.real(4 + a);
      g.dims[a] = read.int64(7 + a);
      for (int b = 0; b < 3; ++b) g.direction[a][b] = read.real(10 + 3 * a + b);
    }
    Result<Image> image = decode_image(blob, g);
    if (!image.ok()) return Status(image.status().code(), "image " + sha + ": " + image.status().message());
    SOIQ_ASSIGN_OR_RETURN(const EncodedImage encoded, encode_image(*image));
    if (encoded.sha256 != sha) return data_loss("image " + sha + " decodes to an image of sha256 " + encoded.sha256);
    write.reset();
    write.bind_blob(1, encoded.blob.data(), encoded.blob.size());
    write.bind(2, sha);
    SOIQ_RETURN_IF_ERROR(write.step().status());
  }
  return ok_status();
}

Status sqlite_checksum_stored_bytes(Connection& c) {
  SqliteSession session(c);
  return checksum_stored_bytes(session);
}

}  // namespace soiq::db
