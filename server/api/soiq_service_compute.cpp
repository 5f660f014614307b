// SoiqService's computations on stored structures: a conversion, one structure's features, a query.
#include <algorithm>

#include "core/base/run_length_volume.h"
#include "core/features/feature_catalogue.h"
#include "core/voxelize/coverage_1d.h"
#include "server/api/grid_spec.h"
#include "server/api/proto_records.h"
#include "server/api/query_request.h"
#include "server/api/render_request.h"
#include "server/api/rpc_handling.h"
#include "server/app/modality_names.h"
#include "server/app/stored_structure_features.h"
#include "server/app/structure_conversion.h"

namespace soiq::server {
namespace {

constexpr size_t kMaskChunkBytes = 1 << 20;
constexpr size_t kPictureChunkBytes = 1 << 20;  // mask chunks: well under gRPC's 4 MiB message limit
constexpr int kRunsPerMessage = 65536;

FillRule fill_rule_of(v1::FillRule f) { return f == v1::EVEN_ODD ? FillRule::kEvenOdd : FillRule::kNonZero; }

// The runs as RunBatch messages after the summary.
Status write_runs(const RunLengthVolume& volume, int64_t ny, grpc::ServerWriter<v1::ConvertResponse>& writer) {
  v1::ConvertResponse batch;
  for (int64_t l = 0; l < volume.line_count(); ++l) {
    for (int64_t r = volume.line_start[l]; r < volume.line_start[l + 1]; ++r) {
      v1::RunBatch* b = batch.mutable_runs();
      b->add_j(int32_t(l % ny));
      b->add_k(int32_t(l / ny));
      b->add_begin(volume.runs[r].begin);
      b->add_end(volume.runs[r].end);
      if (b->j_size() == kRunsPerMessage) {
        if (!writer.Write(batch)) return Status(StatusCode::kCancelled, "the client closed the conversion");
        batch.Clear();
      }
    }
  }
  if (batch.has_runs() && !writer.Write(batch))
    return Status(StatusCode::kCancelled, "the client closed the conversion");
  return ok_status();
}

// Convert's first message: the grid, the voxels, the time taken and the surface's defects.
v1::ConvertSummary summary_of(const StructureConversion& c, double milliseconds) {
  v1::ConvertSummary summary;
  *summary.mutable_geometry() = to_proto(c.grid.geometry);
  summary.set_voxel_count(voxel_count(c.voxelization.volume));
  summary.set_volume_mm3(double(summary.voxel_count()) * c.grid.geometry.voxel_volume_mm3());
  summary.set_milliseconds(milliseconds);
  summary.set_defects(c.structure.robust ? describe(c.voxelization.defects) : "closed (checked at upload)");
  return summary;
}

// Convert's first message for coverage fractions: the voxels with any coverage, the volume as the
// sum of the fractions.
v1::ConvertSummary summary_of(const StructureCoverage& c, double milliseconds) {
  v1::ConvertSummary summary;
  *summary.mutable_geometry() = to_proto(c.grid.geometry);
  summary.set_voxel_count(voxel_count(any_coverage(c.coverage)));
  summary.set_volume_mm3(covered_voxels(c.coverage) * c.grid.geometry.voxel_volume_mm3());
  summary.set_milliseconds(milliseconds);
  summary.set_defects("closed (checked at upload)");
  summary.set_oversample(c.coverage.lines_per_voxel);
  summary.set_partial_voxels(int64_t(c.coverage.partial.size()));
  return summary;
}

// NIfTI bytes after the summary, in chunks under gRPC's message limit.
Status write_nifti_chunks(const std::string& bytes, grpc::ServerWriter<v1::ConvertResponse>& writer) {
  for (size_t at = 0; at < bytes.size(); at += kMaskChunkBytes) {
    v1::ConvertResponse chunk;
    chunk.set_nifti_chunk(bytes.substr(at, kMaskChunkBytes));
    if (!writer.Write(chunk)) return Status(StatusCode::kCancelled, "the client closed the conversion");
  }
  return ok_status();
}

// A FeaturesRequest as the app's FeatureAsk; images without names ask every shape and intensity
// feature.
Result<FeatureAsk> ask_of(const v1::FeaturesRequest& request) {
  FeatureAsk ask;
  ask.names.assign(request.features().begin(), request.features().end());
  for (const std::string& r : request.regions()) {
    SOIQ_ASSIGN_OR_RETURN(RegionSpec spec, parse_region(r));
    ask.regions.push_back(spec);
  }
  for (const std::string& image : request.images()) ask.images.push_back(dicom_modality(image));
  if (request.images_size() > 0 && request.features_size() == 0) {
    ask.names = shape_feature_names();
    for (const auto& n : intensity_feature_names())
      if (std::find(ask.names.begin(), ask.names.end(), n) == ask.names.end()) ask.names.push_back(n);
  }
  SOIQ_RETURN_IF_ERROR(check_enum(request.interpolation(), v1::Interpolation_IsValid, "interpolation"));
  ask.interpolation = request.interpolation() == v1::LINEAR ? Interpolation::kLinear : Interpolation::kNearest;
  SOIQ_ASSIGN_OR_RETURN(ask.grid, grid_choice(request.grid()));
  SOIQ_RETURN_IF_ERROR(complete_feature_ask(ask));
  return ask;
}

}  // namespace

grpc::Status SoiqService::Convert(grpc::ServerContext* ctx, const v1::ConvertRequest* request,
                                  grpc::ServerWriter<v1::ConvertResponse>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    const Clock::time_point start = Clock::now();
    SOIQ_RETURN_IF_ERROR(check_enum(request->fill_rule(), v1::FillRule_IsValid, "fill_rule"));
    SOIQ_RETURN_IF_ERROR(check_enum(request->encoding(), v1::VolumeEncoding_IsValid, "encoding"));
    SOIQ_RETURN_IF_ERROR(check_enum(request->fraction_type(), v1::FractionType_IsValid, "fraction_type"));
    SOIQ_ASSIGN_OR_RETURN(const GridChoice choice, grid_choice(request->grid()));
    const bool runs = request->encoding() == v1::RUNS;
    const int oversample = request->oversample();
    if (oversample < 0 || oversample > kMaxLinesPerVoxel) {
      return invalid_argument("oversample must be 0 (a binary mask) or 1 to " + std::to_string(kMaxLinesPerVoxel) +
                              " (coverage fractions), not " + std::to_string(oversample));
    }
    if (oversample > 0 && runs) return invalid_argument("coverage fractions come as NIfTI: ask for NIFTI_GZ, not RUNS");
    if (oversample == 0 && request->fraction_type() != v1::FRACTION_UINT8) {
      return invalid_argument("fraction_type applies to coverage fractions: set oversample to 1-8");
    }
    std::string bytes;
    v1::ConvertResponse first;
    if (oversample > 0) {
      const bool float32 = request->fraction_type() == v1::FRACTION_FLOAT32;
      SOIQ_ASSIGN_OR_RETURN(
          const StructureCoverage c,
          cover_structure(store_, features_, pool_, request->structure_id(), choice, fill_rule_of(request->fill_rule()),
                          oversample, float32 ? 4 : 1, [&] { return stop_status(*ctx); }));
      SOIQ_ASSIGN_OR_RETURN(bytes, fraction_nifti_bytes(c.coverage, float32, config_.max_grid_voxels));
      *first.mutable_summary() = summary_of(c, ms_since(start));
    } else {
      SOIQ_ASSIGN_OR_RETURN(
          const StructureConversion c,
          convert_structure(store_, features_, pool_, request->structure_id(), choice,
                            fill_rule_of(request->fill_rule()), !runs, [&] { return stop_status(*ctx); }));
      // Encoded before the summary, which tells the client how many bytes follow.
      if (!runs) {
        SOIQ_ASSIGN_OR_RETURN(bytes, mask_nifti_bytes(c.voxelization.volume, config_.max_grid_voxels));
      }
      *first.mutable_summary() = summary_of(c, ms_since(start));
      first.mutable_summary()->set_nifti_bytes(int64_t(bytes.size()));
      if (!writer->Write(first)) return Status(StatusCode::kCancelled, "the client closed the conversion");
      if (runs) return write_runs(c.voxelization.volume, c.grid.geometry.dims[1], *writer);
      return write_nifti_chunks(bytes, *writer);
    }
    first.mutable_summary()->set_nifti_bytes(int64_t(bytes.size()));
    if (!writer->Write(first)) return Status(StatusCode::kCancelled, "the client closed the conversion");
    return write_nifti_chunks(bytes, *writer);
  });
}

grpc::Status SoiqService::ComputeFeatures(grpc::ServerContext* ctx, const v1::FeaturesRequest* request,
                                          v1::FeaturesResponse* response) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(const FeatureAsk ask, ask_of(*request));
    SOIQ_ASSIGN_OR_RETURN(const StoredStructureFeatures f,
                          stored_structure_features(store_, features_, pool_, request->structure_id(), ask));
    if (!f.from_cache) {
      v1::Timing* t = response->add_timings();
      t->set_part("conversion and features");
      t->set_milliseconds(f.compute_ms);
    }
    response->set_from_cache(f.from_cache);
    *response->mutable_geometry() = to_proto(f.plan.grid.geometry);
    for (const WantedValue& w : f.plan.wants) {
      v1::FeatureValue* out = response->add_features();
      out->set_name(w.name);
      out->set_region(w.region);
      out->set_image(w.image);
      for (double x : f.values.at(w.entry)) out->add_value(x);
    }
    return ok_status();
  });
}

grpc::Status SoiqService::Query(grpc::ServerContext* ctx, const v1::QueryRequest* request,
                                grpc::ServerWriter<v1::QueryEvent>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(const soiq::server::Query query, parse_query(*request, queries_.limits().result_cap));
    auto write = [&](const v1::QueryEvent& e) {
      return writer->Write(e) ? ok_status() : Status(StatusCode::kCancelled, "the client closed the query stream");
    };
    const QueryOutput out{[&](const QueryProgress& p) { return write(to_event(p)); },
                          [&](QueryRow&& row) { return write(to_event(row)); }};
    SOIQ_ASSIGN_OR_RETURN(const QuerySummary summary, queries_.run(
                                                          query, [&] { return stop_status(*ctx); }, out));
    return write(to_event(summary));
  });
}

grpc::Status SoiqService::Render(grpc::ServerContext* ctx, const v1::RenderRequest* request,
                                 grpc::ServerWriter<v1::RenderResponse>* writer) {
  return handle(__func__, *ctx, [&]() -> Status {
    SOIQ_ASSIGN_OR_RETURN(const RenderAsk ask, render_ask(*request));
    SOIQ_ASSIGN_OR_RETURN(
        const RenderedPicture picture,
        render_structure(store_, features_, pool_, request->structure_id(), ask, [&] { return stop_status(*ctx); }));
    v1::RenderResponse head;
    v1::RenderInfo& info = *head.mutable_info();
    info.set_media_type(render::media_type(picture.format));
    info.set_series_uid(picture.series_uid);
    info.set_plane(proto_plane(picture.plane));
    for (const int64_t k : picture.slices) info.add_slices(k);
    info.set_slice_count(picture.slice_count);
    info.set_window_center(picture.window.center);
    info.set_window_width(picture.window.width);
    info.set_width(picture.size.width);
    info.set_height(picture.size.height);
    info.set_size_bytes(int64_t(picture.bytes.size()));
    if (!writer->Write(head)) return Status(StatusCode::kCancelled, "the client closed the picture");
    for (size_t at = 0; at < picture.bytes.size(); at += kPictureChunkBytes) {
      v1::RenderResponse chunk;
      chunk.set_chunk(picture.bytes.substr(at, kPictureChunkBytes));
      if (!writer->Write(chunk)) return Status(StatusCode::kCancelled, "the client closed the picture");
    }
    return ok_status();
  });
}

}  // namespace soiq::server
