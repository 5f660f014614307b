#include "bench/surface_codec_bench.h"

#include <lz4.h>
#include <zstd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bench/query_cohort.h"
#include "client/cohort/deformed_ellipsoid.h"
#include "client/cohort/split_mix_64.h"
#include "core/base/triangle_mesh.h"
#include "core/geometry/primitives.h"
#include "core/io/marching_cubes.h"
#include "core/io/read_image.h"
#include "db/deflate.h"
#include "db/image_blob.h"
#include "db/surface_blob.h"

namespace soiq::bench {
namespace {

// The canonical payload without header: vertices as float64 x y z per vertex, then uint32 triples.
std::string canonical(const TriangleMesh& m) {
  std::string out(m.vertices_mm.size() * 24 + m.triangles.size() * 12, '\0');
  std::memcpy(out.data(), m.vertices_mm.data(), m.vertices_mm.size() * 24);
  std::memcpy(out.data() + m.vertices_mm.size() * 24, m.triangles.data(), m.triangles.size() * 12);
  return out;
}

// The "planes" transform: each coordinate axis as a plane of int64 bit-pattern deltas, each
// triangle corner as a plane of zigzagged int32 deltas, every plane byte-shuffled.
std::string planes(const TriangleMesh& m) {
  const size_t nv = m.vertices_mm.size(), nt = m.triangles.size();
  std::string out(nv * 24 + nt * 12, '\0');
  uint8_t* o = reinterpret_cast<uint8_t*>(out.data());
  for (int a = 0; a < 3; ++a) {
    uint64_t prev = 0;
    uint8_t* base = o + a * nv * 8;
    for (size_t i = 0; i < nv; ++i) {
      uint64_t bits;
      std::memcpy(&bits, &m.vertices_mm[i][a], 8);
      const uint64_t d = bits - prev;
      prev = bits;
      for (int b = 0; b < 8; ++b) base[b * nv + i] = uint8_t(d >> (8 * b));
    }
  }
  o += nv * 24;
  for (int k = 0; k < 3; ++k) {
    int32_t prev = 0;
    uint8_t* base = o + k * nt * 4;
    for (size_t t = 0; t < nt; ++t) {
      const int32_t v = m.triangles[t][k];
      const int32_t d = v - prev;
      prev = v;
      const uint32_t z = (uint32_t(d) << 1) ^ uint32_t(d >> 31);
      for (int b = 0; b < 4; ++b) base[b * nt + t] = uint8_t(z >> (8 * b));
    }
  }
  return out;
}

TriangleMesh unplanes(const std::string& in, size_t nv, size_t nt) {
  TriangleMesh m;
  m.vertices_mm.resize(nv);
  m.triangles.resize(nt);
  const uint8_t* p = reinterpret_cast<const uint8_t*>(in.data());
  for (int a = 0; a < 3; ++a) {
    uint64_t prev = 0;
    const uint8_t* base = p + a * nv * 8;
    for (size_t i = 0; i < nv; ++i) {
      uint64_t d = 0;
      for (int b = 0; b < 8; ++b) d |= uint64_t(base[b * nv + i]) << (8 * b);
      prev += d;
      std::memcpy(&m.vertices_mm[i][a], &prev, 8);
    }
  }
  p += nv * 24;
  for (int k = 0; k < 3; ++k) {
    int32_t prev = 0;
    const uint8_t* base = p + k * nt * 4;
    for (size_t t = 0; t < nt; ++t) {
      uint32_t z = 0;
      for (int b = 0; b < 4; ++b) z |= uint32_t(base[b * nt + t]) << (8 * b);
      prev += int32_t((z >> 1) ^ (0u - (z & 1)));
      m.triangles[t][k] = prev;
    }
  }
  return m;
}

// Version 1's canonical bytes: its 32-byte header, then the payload.
std::string canonical_v1(const TriangleMesh& m) {
  std::string header(32, '\0');
  const uint32_t version = 1;
  const uint64_t nv = m.vertices_mm.size(), nt = m.triangles.size();
  std::memcpy(header.data(), "SOIQSURF", 8);
  std::memcpy(header.data() + 8, &version, 4);
  std::memcpy(header.data() + 16, &nv, 8);
  std::memcpy(header.data() + 24, &nt, 8);
  return header + canonical(m);
}

TriangleMesh uncanonical(const std::string& in, size_t nv, size_t nt) {
  TriangleMesh m;
  m.vertices_mm.resize(nv);
  m.triangles.resize(nt);
  std::memcpy(m.vertices_mm.data(), in.data(), nv * 24);
  std::memcpy(m.triangles.data(), in.data() + nv * 24, nt * 12);
  return m;
}

std::string lz4(const std::string& in) {
  std::string out(size_t(LZ4_compressBound(int(in.size()))), '\0');
  out.resize(size_t(LZ4_compress_default(in.data(), out.data(), int(in.size()), int(out.size()))));
  return out;
}
std::string unlz4(const std::string& in, size_t size) {
  std::string out(size, '\0');
  LZ4_decompress_safe(in.data(), out.data(), int(in.size()), int(size));
  return out;
}
std::string zstd(const std::string& in, int level) {
  std::string out(ZSTD_compressBound(in.size()), '\0');
  out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), level));
  return out;
}
std::string unzstd(const std::string& in, size_t size) {
  std::string out(size, '\0');
  ZSTD_decompress(out.data(), size, in.data(), in.size());
  return out;
}

struct Candidate {
  const char* name;
  std::function<std::string(const TriangleMesh&)> encode;
  std::function<TriangleMesh(const std::string&, size_t, size_t)> decode;
};

std::vector<Candidate> candidates() {
  return {
      {"zlib-1 canonical (version 1 blobs)",
       [](const TriangleMesh& m) {
         const std::string bytes = canonical_v1(m);
         return db::deflate_bytes(bytes.data(), bytes.size()).value();
       },
       [](const std::string& b, size_t nv, size_t nt) {
         return uncanonical(db::inflate_bytes(b, 1ull << 34).value().substr(32), nv, nt);
       }},
      // value() of the temporary Result moves the mesh out; operator* would give a const& and copy
      // it, adding a memcpy of the decoded bytes to the decode column.
      {"soiq delta planes + lz4 + crc32 (version 3 blobs)",
       [](const TriangleMesh& m) { return db::encode_surface(m)->blob; },
       [](const std::string& b, size_t, size_t) { return db::decode_surface(b).value(); }},
      // Version 3 is version 2's bytes after a 4-byte CRC-32 (db/surface_blob.cpp): the same blob
      // without it is what version 3's decode costs beyond version 2's (its encode row includes
      // version 3's encode).
      {"the same without the crc32 (version 2 blobs)",
       [](const TriangleMesh& m) { return "SOIQSRF2" + db::encode_surface(m)->blob.substr(12); },
       [](const std::string& b, size_t, size_t) { return db::decode_surface(b).value(); }},
      {"lz4 canonical", [](const TriangleMesh& m) { return lz4(canonical(m)); },
       [](const std::string& b, size_t nv, size_t nt) { return uncanonical(unlz4(b, nv * 24 + nt * 12), nv, nt); }},
      {"zstd-1 canonical", [](const TriangleMesh& m) { return zstd(canonical(m), 1); },
       [](const std::string& b, size_t nv, size_t nt) { return uncanonical(unzstd(b, nv * 24 + nt * 12), nv, nt); }},
      {"lz4 planes", [](const TriangleMesh& m) { return lz4(planes(m)); },
       [](const std::string& b, size_t nv, size_t nt) { return unplanes(unlz4(b, nv * 24 + nt * 12), nv, nt); }},
      {"zstd-1 planes", [](const TriangleMesh& m) { return zstd(planes(m), 1); },
       [](const std::string& b, size_t nv, size_t nt) { return unplanes(unzstd(b, nv * 24 + nt * 12), nv, nt); }},
      {"zstd-3 planes", [](const TriangleMesh& m) { return zstd(planes(m), 3); },
       [](const std::string& b, size_t nv, size_t nt) { return unplanes(unzstd(b, nv * 24 + nt * 12), nv, nt); }},
  };
}

// The median wall time of `runs` calls of `f`.
double median_ms(int runs, const std::function<void()>& f) {
  std::vector<double> ms;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

// The minimum and median wall time of `runs` calls of each of `a` and `b`, called in turn (a, b,
// a, b, ...), so that a noisy neighbour or a clock step weighs on both alike.
struct PairedMs {
  double a_min, a_median, b_min, b_median;
};
PairedMs paired_ms(int runs, const std::function<void()>& a, const std::function<void()>& b) {
  std::vector<double> ta, tb;
  auto time = [](const std::function<void()>& f, std::vector<double>& ms) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  };
  for (int r = 0; r < runs; ++r) {
    time(a, ta);
    time(b, tb);
  }
  std::sort(ta.begin(), ta.end());
  std::sort(tb.begin(), tb.end());
  return {ta.front(), ta[ta.size() / 2], tb.front(), tb[tb.size() / 2]};
}

bool same(const TriangleMesh& a, const TriangleMesh& b) {
  return a.vertices_mm.size() == b.vertices_mm.size() && a.triangles == b.triangles &&
         std::memcmp(a.vertices_mm.data(), b.vertices_mm.data(), a.vertices_mm.size() * 24) == 0;
}

TriangleMesh float32_rounded(TriangleMesh m) {
  for (Vec3& v : m.vertices_mm)
    for (double& x : v) x = double(float(x));
  return m;
}

// The image blob's two versions (db/image_blob.h) on the query benchmark's MR image and, with
// --image, a real one: what a cold query pays per study.
void print_image_codecs(int runs, const std::string& path) {
  std::vector<std::pair<std::string, Image>> images;
  QueryCohortSize size;
  for (const CohortPatient& p : query_cohort_patients(size, 20250409)) {
    if (!p.matched) continue;
    images.emplace_back("query-bench MR (synthetic)", matched_image(p, size));
    break;
  }
  if (!path.empty()) {
    Result<Image> image = read_image(path);
    if (image.ok()) images.emplace_back(path, std::move(image).value());
  }
  std::printf(
      "\n| image | voxels | codec | bytes | vs zlib | encode ms | decode ms |\n|---|---:|---|---:|---:|---:|---:|\n");
  // Named references, not a structured binding: clang 14 (the sanitizer build) cannot capture one.
  for (const auto& named : images) {
    const auto& name = named.first;
    const auto& image = named.second;
    const size_t raw = image.voxels.size() * sizeof(float);
    std::string v1, v2;
    const double enc1 = median_ms(runs, [&] { v1 = *db::deflate_bytes(image.voxels.data(), raw); });
    const double enc2 = median_ms(runs, [&] { v2 = db::encode_image(image)->blob; });
    Image back1, back2;
    const double dec1 = median_ms(runs, [&] { back1 = db::decode_image(v1, image.geometry).value(); });
    const double dec2 = median_ms(runs, [&] { back2 = db::decode_image(v2, image.geometry).value(); });
    for (const auto& [codec, blob, back, enc, dec] :
         {std::tuple{"zlib (version 1 blobs)", &v1, &back1, enc1, dec1},
          std::tuple{"soiq delta planes + lz4 + adler32 (version 2 blobs)", &v2, &back2, enc2, dec2}}) {
      const bool lossless = std::memcmp(back->voxels.data(), image.voxels.data(), raw) == 0;
      std::printf("| %s | %zu | %s%s | %zu | %.2f | %.2f | %.2f |\n", name.c_str(), image.voxels.size(), codec,
                  lossless ? "" : " (NOT LOSSLESS)", blob->size(), double(blob->size()) / double(v1.size()), enc, dec);
    }
  }
}

// What decoding a version 3 blob costs against the least any decoder pays: a memcpy of the bytes
// it writes (vertices as float64 xyz, triangles as int32 triples).
//
// Both sides write a TriangleMesh they allocate, as a cold query does (it decodes into a mesh of
// its own and frees it when it is done): the decoder's, and a copy of the decoded mesh, which
// std::vector's copy constructor allocates uninitialised and fills by memcpy. Each run frees the
// previous run's mesh when it assigns the new one, on both sides, so both see the same sizes of
// allocation in the same order, and pay alike whatever malloc does with them (fresh pages from
// the kernel, with a fault on each first touch, or pages of its own heap). Zeroing is not part of
// the baseline: a decoder that zeroes what it then overwrites pays for it.
void print_decode_vs_memcpy(int runs, const std::vector<std::pair<std::string, TriangleMesh>>& meshes) {
  std::printf(
      "\n| mesh | triangles | decoded bytes | decode ms | memcpy ms | decode / memcpy | decode ms (min) | "
      "memcpy ms (min) | decode / memcpy (min) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& named : meshes) {
    const TriangleMesh& mesh = named.second;
    const std::string blob = db::encode_surface(mesh)->blob;
    const size_t bytes = mesh.vertices_mm.size() * sizeof(Vec3) + mesh.triangles.size() * sizeof(mesh.triangles[0]);
    TriangleMesh decoded, copied;
    const PairedMs t = paired_ms(
        runs, [&] { decoded = db::decode_surface(blob).value(); }, [&] { copied = TriangleMesh(mesh); });
    std::printf("| %s | %zu | %zu%s | %.3f | %.3f | %.2f | %.3f | %.3f | %.2f |\n", named.first.c_str(),
                mesh.triangles.size(), bytes, same(mesh, decoded) && same(mesh, copied) ? "" : " (NOT LOSSLESS)",
                t.a_median, t.b_median, t.a_median / t.b_median, t.a_min, t.b_min, t.a_min / t.b_min);
  }
}

}  // namespace

int run_surface_codec_bench(const CliArgs& args) {
  const Result<int> runs_arg = args.get_int("--runs", 20);
  if (!runs_arg.ok() || *runs_arg < 1) {
    std::fprintf(stderr, "soiq-bench codec: --runs must be a whole number >= 1\n");
    return 2;
  }
  const int runs = *runs_arg;
  const std::string label = args.get("--label", "");
  std::vector<std::pair<std::string, TriangleMesh>> meshes;
  meshes.emplace_back("uv sphere, 100k triangles, float64", uv_sphere_with_triangles({1.5, -2.25, 30.125}, 25, 100000));
  meshes.emplace_back("uv sphere, 400k triangles, float64", uv_sphere_with_triangles({1.5, -2.25, 30.125}, 25, 400000));
  const cohort::Ellipsoid e{{12.3, -40.1, 20.7}, {10, 7, 5}};
  cohort::SplitMix64 random(7);
  meshes.emplace_back("query-bench structure, 20k triangles",
                      cohort::deformed_ellipsoid(e, cohort::draw_radial_bump(random), 20000));
  if (!label.empty()) {
    Result<Image> image = read_image(label);
    if (image.ok()) {
      Mask mask = mask_from_image(*image);
      Result<TriangleMesh> mc = marching_cubes(mask);
      if (mc.ok()) {
        meshes.emplace_back("marching cubes of " + label, *mc);
        meshes.emplace_back("same, float32 coordinates (an STL upload)", float32_rounded(*mc));
      }
    }
  }
  if (args.has("--decode-only")) {
    print_decode_vs_memcpy(runs, meshes);
    return 0;
  }
  std::printf(
      "| mesh | triangles | codec | bytes | vs zlib | encode ms | decode ms |\n|---|---:|---|---:|---:|---:|---:|\n");
  for (const auto& named : meshes) {  // as above: clang 14 captures no structured binding
    const auto& name = named.first;
    const auto& mesh = named.second;
    const size_t nv = mesh.vertices_mm.size(), nt = mesh.triangles.size();
    size_t zlib_bytes = 0;
    for (const Candidate& c : candidates()) {
      std::string blob;
      const double enc = median_ms(runs, [&] { blob = c.encode(mesh); });
      TriangleMesh back;
      const double dec = median_ms(runs, [&] { back = c.decode(blob, nv, nt); });
      if (zlib_bytes == 0) zlib_bytes = blob.size();
      std::printf("| %s | %zu | %s%s | %zu | %.2f | %.3f | %.3f |\n", name.c_str(), nt, c.name,
                  same(mesh, back) ? "" : " (NOT LOSSLESS)", blob.size(), double(blob.size()) / double(zlib_bytes), enc,
                  dec);
    }
  }
  print_decode_vs_memcpy(runs, meshes);
  print_image_codecs(runs, args.get("--image", ""));
  return 0;
}

}  // namespace soiq::bench
