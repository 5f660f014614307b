#include "server/app/store_verify.h"

#include <cinttypes>
#include <cstdio>
#include <map>

#include "db/cached_value.h"
#include "db/image_blob.h"
#include "db/surface_blob.h"

namespace soiq::server {
namespace {

std::string structures(const std::vector<int64_t>& ids) {
  if (ids.empty()) return "no structure";
  std::string out = ids.size() == 1 ? "structure " : "structures ";
  for (size_t i = 0; i < ids.size(); ++i) out += (i ? ", " : "") + std::to_string(ids[i]);
  return out;
}

// What is wrong with a stored surface blob ("" when nothing): its decode's error, or a mesh that is
// not the one its key names.
std::string surface_damage(const db::StoredItem& item) {
  Result<TriangleMesh> mesh = db::decode_surface(item.bytes);
  if (!mesh.ok()) return mesh.status().message();
  const std::string got = db::surface_sha256(*mesh);
  if (got != item.key) return "decodes to a mesh of sha256 " + got + ", not the one it is stored under";
  return "";
}

std::string image_damage(const db::StoredItem& item) {
  Result<Image> image = db::decode_image(item.bytes, item.geometry);
  if (!image.ok()) return image.status().message();
  const std::string got = db::image_sha256(*image);
  if (got != item.key) return "decodes to an image of sha256 " + got + ", not the one it is stored under";
  return "";
}

// A kept file is its sha256's bytes, nothing else to decode.
std::string instance_file_damage(const db::StoredItem& item) {
  const std::string got = db::sha256_hex(item.bytes.data(), item.bytes.size());
  if (got == item.key) return "";
  return "its bytes hash to " + got + ", not to the key it is stored under";
}

// One scrub: the report, and each surface's structures, which name a cached value's users.
struct Scrub {
  VerifyReport report;
  std::map<std::string, std::vector<int64_t>> structures_of;

  void surface(const db::StoredItem& item) {
    ++report.surfaces.checked;
    structures_of[item.key] = item.structure_ids;
    const VerifyFinding found{"surface", item.key, structures(item.structure_ids), surface_damage(item)};
    if (!found.problem.empty()) {
      ++report.surfaces.damaged;
      report.damaged.push_back(found);
      return;
    }
    const int version = db::surface_blob_version(item.bytes);
    if (version == 3) return;
    ++report.surfaces.without_checksum;
    report.without_checksum.push_back({"surface", item.key, found.users,
                                       "version " + std::to_string(version) +
                                           " blob, sound by its sha256; soiqd re-encodes it with a checksum when it "
                                           "opens the store"});
  }

  void image(const db::StoredItem& item) {
    ++report.images.checked;
    if (item.series_uid.empty()) {
      // Nothing reads it (a series that held it is gone), and without a grid it cannot be decoded.
      ++report.images.without_checksum;
      report.without_checksum.push_back(
          {"image", item.key, "no series", "not checked: no series holds it, so its grid is unknown"});
      return;
    }
    const VerifyFinding found{"image", item.key, "series " + item.series_uid, image_damage(item)};
    if (found.problem.empty()) return;
    ++report.images.damaged;
    report.damaged.push_back(found);
  }

  void instance_file(const db::StoredItem& item) {
    ++report.instance_files.checked;
    const std::string users = item.series_uid.empty() ? "no instance" : "series " + item.series_uid;
    const VerifyFinding found{"instance file", item.key, users, instance_file_damage(item)};
    if (found.problem.empty()) return;
    ++report.instance_files.damaged;
    report.damaged.push_back(found);
  }

  void instance(const db::StoredItem& item) {
    ++report.instances.checked;
    if (item.instance_crc32 == int64_t(db::instance_row_crc32(item.instance))) return;
    ++report.instances.damaged;
    report.damaged.push_back(
        {"instance", item.key, "series " + item.series_uid, "its stored record no longer matches its checksum"});
  }

  void cached_value(const db::StoredItem& item) {
    ++report.cached_values.checked;
    const db::CachedFeature f{item.key, item.entry, {}};
    const std::string damage = db::cached_value_damage(f, item.bytes);
    if (damage.empty()) {
      if (!db::cached_value_has_checksum(item.bytes)) ++report.cached_values.without_checksum;
      return;
    }
    ++report.cached_values.damaged;
    std::string users = "surface " + item.surface_sha256;
    // A surface stored after its pass is not in the map: its structures go unnamed.
    if (auto it = structures_of.find(item.surface_sha256); it != structures_of.end())
      users += ", " + structures(it->second);
    report.damaged.push_back({"cached value", "'" + item.entry + "' under key '" + item.key + "'", users, damage});
  }
};

}  // namespace

Result<VerifyReport> verify_store(const StoreLocation& at,
                                  const std::function<void(const std::string&, int64_t)>& progress) {
  StoreOpenOptions options;
  options.read_only = true;
  options.read_connections = 1;
  options.connections = 1;
  SOIQ_ASSIGN_OR_RETURN(std::unique_ptr<db::SqlStore> store, open_sql_store(at, options));
  Scrub scrub;
  auto pass = [&](db::StoredKind kind, const std::string& name, int64_t& done,
                  void (Scrub::*check)(const db::StoredItem&)) {
    return store->scan_stored(kind, [&](const db::StoredItem& item) {
      (scrub.*check)(item);
      if (progress) progress(name, done);
      return ok_status();
    });
  };
  // Surfaces first: the cached values name the structures of their surface.
  SOIQ_RETURN_IF_ERROR(pass(db::StoredKind::kSurface, "surfaces", scrub.report.surfaces.checked, &Scrub::surface));
  SOIQ_RETURN_IF_ERROR(pass(db::StoredKind::kImage, "images", scrub.report.images.checked, &Scrub::image));
  SOIQ_RETURN_IF_ERROR(
      pass(db::StoredKind::kCachedValue, "cached values", scrub.report.cached_values.checked, &Scrub::cached_value));
  SOIQ_RETURN_IF_ERROR(pass(db::StoredKind::kInstanceFile, "instance files", scrub.report.instance_files.checked,
                            &Scrub::instance_file));
  SOIQ_RETURN_IF_ERROR(pass(db::StoredKind::kInstance, "instances", scrub.report.instances.checked, &Scrub::instance));
  return std::move(scrub.report);
}

std::vector<std::string> format_verify_report(const VerifyReport& r) {
  std::vector<std::string> lines;
  char line[160];
  for (const auto& [name, c] : {std::pair{"surfaces", &r.surfaces}, std::pair{"images", &r.images},
                                std::pair{"cached values", &r.cached_values},
                                std::pair{"instance files", &r.instance_files}, std::pair{"instances", &r.instances}}) {
    std::snprintf(line, sizeof line,
                  "%-14s %10" PRId64 " checked  %6" PRId64 " damaged  %10" PRId64 " without a checksum", name,
                  c->checked, c->damaged, c->without_checksum);
    lines.emplace_back(line);
  }
  for (const VerifyFinding& f : r.damaged)
    lines.push_back("damaged " + f.kind + " " + f.id + " (" + f.users + "): " + f.problem);
  for (const VerifyFinding& f : r.without_checksum)
    lines.push_back("without a checksum: " + f.kind + " " + f.id + " (" + f.users + "): " + f.problem);
  if (r.sound()) {
    lines.emplace_back("the store is sound");
  } else {
    lines.push_back(
        std::to_string(r.damaged.size()) +
        " damaged: restore the store from a backup, or upload each damaged surface again (an upload "
        "of the same mesh replaces its blob) and import each damaged image's, instance file's or instance's "
        "series again");
  }
  return lines;
}

}  // namespace soiq::server
