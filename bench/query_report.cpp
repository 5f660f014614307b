#include "bench/query_report.h"

#include <cstdio>
#include <string>

namespace soiq::bench {

namespace {

const char* met(double v, double limit) { return v < limit ? "met" : "**not met**"; }

// The cohort, the query, and the load table.
void print_cohort_and_load(const QueryBenchFigures& f) {
  const int64_t matched_patients = f.size.matched;
  std::printf(
      "Cohort: %d patients (sex F/M ~50/50, born 1930-2005, one study 2010-2025, MR 50 %% / CT 35 %% / PT 15 %%);\n"
      "stage 1 (F, MR, study 2020-2023, age at study 60-75) keeps exactly %lld of them: %zu structures\n"
      "(hippocampus, amygdala, caudate, putamen, thalamus, L and R; deformed ellipsoids of %lld-%lld triangles,\n"
      "checked closed with core/geometry/mesh_defects), each study with a %lldx%lldx%lld MR image of 2 mm. The other\n"
      "patients have one structure each on %d shared surface blobs. Database: %.0f MiB. soiqd: --workers %d.\n\n",
      f.size.patients, (long long)matched_patients, f.candidates, (long long)f.min_triangles,
      (long long)f.max_triangles, (long long)f.size.image_dims[0], (long long)f.size.image_dims[1],
      (long long)f.size.image_dims[2], f.size.background_blobs, f.db_mib, f.workers);
  std::printf(
      "Query: `voxel_volume_mm3, sphericity, mean[shell:3, MR]` of every candidate, ordered by\n"
      "voxel_volume_mm3 descending, limit 20, on the default grid (1 mm, axis-aligned, margin grown for the\n"
      "shell), nearest-neighbour sampling of the MR image.\n\n");
  std::printf("| load | items | time | rate |\n|---|---:|---:|---:|\n");
  std::printf("| background patients, SqliteStore::add_structure on tmpfs | %lld | %.1f s | %.0f patients/s |\n",
              (long long)f.background.patients, f.background.seconds,
              double(f.background.patients) / f.background.seconds);
  std::printf(
      "| MR images, `upload_image` (NIfTI, 2 clients) | %lld (%.0f MiB) | %.1f s | %.1f images/s, %.1f MiB/s |\n",
      (long long)f.uploaded.images, double(f.uploaded.image_bytes) / (1 << 20), f.uploaded.image_seconds,
      double(f.uploaded.images) / f.uploaded.image_seconds,
      double(f.uploaded.image_bytes) / (1 << 20) / f.uploaded.image_seconds);
  std::printf(
      "| surfaces, `upload_surface` (binary PLY, 2 clients) | %lld (%.0f MiB, %.1f M triangles) | %.1f s | "
      "%.1f surfaces/s, %.1f MiB/s, %.2f M triangles/s |\n\n",
      (long long)f.uploaded.structures, double(f.uploaded.surface_bytes) / (1 << 20),
      double(f.uploaded.triangles) / 1e6, f.uploaded.surface_seconds,
      double(f.uploaded.structures) / f.uploaded.surface_seconds,
      double(f.uploaded.surface_bytes) / (1 << 20) / f.uploaded.surface_seconds,
      double(f.uploaded.triangles) / 1e6 / f.uploaded.surface_seconds);
}

// Stage 1, cold and warm: best and median of every run, against the targets.
double print_timings(const QueryBenchFigures& f) {
  std::vector<double> s1_server, s1_again, s1_client, cold_client, cold_stage2, warm_client, warm_total;
  for (const ServerRun& r : f.runs) {
    s1_server.push_back(r.stage1.summary.stage1_ms());
    s1_again.push_back(r.stage1_again.summary.stage1_ms());
    s1_client.push_back(r.stage1.client_ms);
    cold_client.push_back(r.cold.client_ms);
    cold_stage2.push_back(r.cold.summary.stage2_ms());
    for (const TimedQuery& w : r.warm) {
      warm_client.push_back(w.client_ms);
      warm_total.push_back(w.summary.total_ms());
    }
  }
  const Stats s1 = stats(f.stage1_ms), s1s = stats(s1_server), s1a = stats(s1_again), s1c = stats(s1_client),
              cc = stats(cold_client), cs2 = stats(cold_stage2), wc = stats(warm_client), wt = stats(warm_total);
  std::printf("| measure | best | median | runs | target |\n|---|---:|---:|---:|---|\n");
  std::printf("| stage 1, SqliteStore::stage1 in-process | %.1f ms | %.1f ms | %zu | |\n", s1.best, s1.median,
              f.stage1_ms.size());
  std::printf(
      "| stage 1, server's stage1_ms (feature-less query, the fresh server's first) | %.1f ms | %.1f ms | %zu | |\n",
      s1s.best, s1s.median, s1_server.size());
  std::printf("| stage 1, server's stage1_ms (the same query again) | %.1f ms | %.1f ms | %zu | <= 10 ms: %s |\n",
              s1a.best, s1a.median, s1_again.size(), met(s1a.best, 10.0001));
  std::printf("| stage 1, client end to end (%zu rows streamed) | %.1f ms | %.1f ms | %zu | |\n", f.candidates,
              s1c.best, s1c.median, s1_client.size());
  std::printf("| cold query, client end to end | %.2f s | %.2f s | %zu | <= 1.0 s: %s |\n", cc.best / 1000,
              cc.median / 1000, cold_client.size(), met(cc.best, 1000.0001));
  std::printf("| cold query, server's stage2_ms | %.2f s | %.2f s | %zu | |\n", cs2.best / 1000, cs2.median / 1000,
              cold_stage2.size());
  std::printf("| warm query, client end to end | %.1f ms | %.1f ms | %zu | <= 15 ms: %s |\n", wc.best, wc.median,
              warm_client.size(), met(wc.best, 15.0001));
  std::printf("| warm query, server's total_ms | %.1f ms | %.1f ms | %zu | |\n\n", wt.best, wt.median,
              warm_total.size());
  return cs2.best;
}

// The query's costs as ratios to what they cannot be cheaper than, each measured in this run: this
// machine's absolute speed varies by half from day to day, its ratios far less.
void print_ratios(const QueryBenchFigures& f, double cold_stage2_best_ms) {
  std::vector<double> warm_total, warm_stage1;
  for (const ServerRun& r : f.runs) {
    for (const TimedQuery& w : r.warm) {
      warm_total.push_back(w.summary.total_ms());
      warm_stage1.push_back(w.summary.stage1_ms());
    }
  }
  const Stats wt = stats(warm_total), ws1 = stats(warm_stage1);
  double one = 0, eight = 0, p95_eight = 0;
  for (const Throughput& t : f.load) {
    if (t.clients == 1) one = t.per_second;
    if (t.clients == 8) {
      eight = t.per_second;
      p95_eight = t.latency.p95;
    }
  }
  const auto at_most = [](double v, double limit) { return v <= limit ? "met" : "**not met**"; };
  std::printf("| ratio | value | from | target |\n|---|---:|---|---|\n");
  const double cold_ratio = cold_stage2_best_ms / f.alone.convert_ms;
  std::printf(
      "| cold query / the same %lld surfaces converted alone on %d threads | %.2fx | stage2_ms %.0f ms (best), "
      "conversions %.0f ms (their read and decode another %.0f ms) | <= 1.5x: %s |\n",
      (long long)f.alone.structures, f.alone.threads, cold_ratio, cold_stage2_best_ms, f.alone.convert_ms,
      f.alone.read_decode_ms, at_most(cold_ratio, 1.5));
  const double cold_with_decode = cold_stage2_best_ms / (f.alone.convert_ms + f.alone.read_decode_ms);
  std::printf("| cold query / the same surfaces read, decoded and converted alone | %.2fx | | |\n", cold_with_decode);
  const double warm_ratio = wt.best / ws1.best;
  std::printf("| warm query's server total_ms / its stage1_ms | %.2fx | %.1f ms / %.1f ms (bests) | <= 1.5x: %s |\n",
              warm_ratio, wt.best, ws1.best, at_most(warm_ratio, 1.5));
  if (one > 0 && eight > 0) {
    const double scaling = eight / one;
    std::printf(
        "| 8 clients' queries/s / 1 client's | %.2fx | %.1f / %.1f q/s, p95 at 8 clients %.1f ms | >= 1.9x: %s |\n",
        scaling, eight, one, p95_eight, scaling >= 1.9 ? "met" : "**not met**");
  }
  // Bests of repeated runs on both sides: the first query a fresh server answers also pays for its
  // first statements and pages, whatever it asks (shown beside, not in the ratio).
  std::vector<double> after, stored;
  for (const TimedQuery& t : f.precompute.benchmark_again) after.push_back(t.client_ms);
  for (const TimedQuery& t : f.precompute.precomputed_set) stored.push_back(t.client_ms);
  if (!after.empty() && !stored.empty()) {
    const double r = stats(after).best / stats(stored).best;
    std::printf(
        "| benchmark query after precompute / query of stored values only (clients) | %.2fx | %.1f ms / %.1f ms "
        "(bests of %zu; the first query after precompute %.1f ms) | <= 2x: %s |\n",
        r, stats(after).best, stats(stored).best, after.size(), f.precompute.benchmark_after.client_ms, at_most(r, 2));
  }
  std::printf("\n");
}

void print_concurrent_clients(const QueryBenchFigures& f) {
  std::printf("Concurrent clients repeating the warm query for %.0f s each (own channel per client):\n\n", f.seconds);
  std::printf("| clients | queries | queries/s | p50 | p95 |\n|---:|---:|---:|---:|---:|\n");
  for (const Throughput& t : f.load)
    std::printf("| %d | %lld | %.1f | %.1f ms | %.1f ms |\n", t.clients, (long long)t.queries, t.per_second,
                t.latency.median, t.latency.p95);
}

// Where the cold time goes, part by part, beside the server's own cold stage 2.
void print_breakdown(const QueryBenchFigures& f, double cold_stage2_best_ms) {
  std::printf(
      "\nWhere the cold time goes: the same %lld structures (%.1f M triangles, %.1f M voxels inside, %.1f M\n"
      "in the shells), part by part in one thread of soiq-bench (cold_breakdown.h), summed:\n\n",
      (long long)f.breakdown.structures, double(f.breakdown.triangles) / 1e6, double(f.breakdown.voxels) / 1e6,
      double(f.breakdown.shell_voxels) / 1e6);
  std::printf("| part | total | per structure | share |\n|---|---:|---:|---:|\n");
  double sum = 0;
  for (const auto& [part, ms] : f.breakdown.parts_ms)
    if (part.rfind("(before)", 0) != 0) sum += ms;
  for (const auto& [part, ms] : f.breakdown.parts_ms)
    std::printf(
        "| %s | %.0f ms | %.2f ms | %s |\n", part.c_str(), ms, ms / double(f.breakdown.structures),
        part.rfind("(before)", 0) == 0 ? "(not in sum)" : (std::to_string(int(100 * ms / sum + 0.5)) + " %").c_str());
  std::printf("| **sum (server's path)** | %.0f ms | %.2f ms | |\n", sum, sum / double(f.breakdown.structures));
  std::printf("| whole pass, one thread (stage 1 %.0f ms and the (before) parts included) | %.0f ms | | |\n",
              f.breakdown.stage1_ms, f.breakdown.total_ms);
  std::printf("| server's cold stage 2 on %d workers (best) | %.0f ms | | |\n\n", f.workers, cold_stage2_best_ms);
}

// Precompute: the queue's drain, then queries on what it stored.
void print_precompute(const QueryBenchFigures& f) {
  const PrecomputeFigures& p = f.precompute;
  std::vector<double> set_client, set_total, filter_client, filter_stage1;
  for (const TimedQuery& t : p.precomputed_set) {
    set_client.push_back(t.client_ms);
    set_total.push_back(t.summary.total_ms());
  }
  for (const TimedQuery& t : p.content_filter) {
    filter_client.push_back(t.client_ms);
    filter_stage1.push_back(t.summary.stage1_ms());
  }
  const Stats sc = stats(set_client), st = stats(set_total), fc = stats(filter_client), fs = stats(filter_stage1);
  const int64_t kept = p.content_filter.empty() ? 0 : p.content_filter[0].summary.stage1_candidates();
  std::printf(
      "Precompute (`soiqd --precompute on`, the default) on a copy of the loaded database, whose queue holds every\n"
      "structure: the %lld background structures share %d surfaces (one computation each, then a cache read),\n"
      "the %zu matched ones are computed each (volume, surface area, sphericity, elongation, flatness, maximum\n"
      "3D diameter; mean, minimum, maximum inside and in a 3 mm shell on the MR image), at nice 19 in one\n"
      "thread of soiqd.\n\n",
      (long long)f.background.structures, f.size.background_blobs, f.candidates);
  std::printf("| measure | best | median | runs | target |\n|---|---:|---:|---:|---|\n");
  std::printf("| precompute: %lld queued structures drained | %.1f s (%.0f structures/s) | | 1 | |\n",
              (long long)p.queued, p.drain_s, double(p.queued) / p.drain_s);
  std::printf("| benchmark query after precompute, client (the first) | %.1f ms | | 1 | <= 60 ms: %s |\n",
              p.benchmark_after.client_ms, met(p.benchmark_after.client_ms, 60.0001));
  std::vector<double> again;
  for (const TimedQuery& t : p.benchmark_again) again.push_back(t.client_ms);
  const Stats ag = stats(again);
  std::printf("| same, repeated, client | %.1f ms | %.1f ms | %zu | |\n", ag.best, ag.median, again.size());
  std::printf(
      "| query of stored values only (volume, sphericity, mean inside; %zu candidates), client | %.1f ms | %.1f ms | "
      "%zu | <= 60 ms: %s |\n",
      f.candidates, sc.best, sc.median, set_client.size(), met(sc.best, 60.0001));
  std::printf("| same, server's total_ms | %.1f ms | %.1f ms | %zu | |\n", st.best, st.median, set_total.size());
  std::printf(
      "| content filter `voxel_volume_mm3 > %.0f`, no stage-1 filter, over %lld structures (%lld kept), client | "
      "%.1f ms | %.1f ms | %zu | |\n",
      p.threshold_mm3, (long long)p.structures, (long long)kept, fc.best, fc.median, filter_client.size());
  std::printf("| same, server's stage1_ms (the index search) | %.1f ms | %.1f ms | %zu | |\n\n", fs.best, fs.median,
              filter_stage1.size());
  const IngestFigures& in = f.ingest_precompute_on;
  std::printf(
      "Ingest of the %lld matched patients (2 clients; an image, then 10 surfaces each) to a fresh soiqd, with\n"
      "precompute off (the load above) and on:\n\n",
      (long long)in.uploaded.patients);
  std::printf("| precompute | surfaces/s | images/s | until every structure is precomputed |\n|---|---:|---:|---:|\n");
  std::printf("| off | %.1f | %.1f | |\n", double(f.uploaded.structures) / f.uploaded.surface_seconds,
              double(f.uploaded.images) / f.uploaded.image_seconds);
  std::printf("| on | %.1f | %.1f | %.1f s (%.1f structures/s) |\n\n",
              double(in.uploaded.structures) / in.uploaded.surface_seconds,
              double(in.uploaded.images) / in.uploaded.image_seconds, in.until_precomputed_s,
              double(in.uploaded.structures) / in.until_precomputed_s);
}

}  // namespace

void print_query_report(const QueryBenchFigures& f) {
  print_cohort_and_load(f);
  const double cold_stage2_best_ms = print_timings(f);
  print_concurrent_clients(f);
  print_breakdown(f, cold_stage2_best_ms);
  print_precompute(f);
  print_ratios(f, cold_stage2_best_ms);
}

}  // namespace soiq::bench
