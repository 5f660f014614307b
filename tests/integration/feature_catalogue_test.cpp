// Every feature of the catalogue (core/features/feature_catalogue.h), computed three ways on one structure
// and one grid: by soiqd over gRPC, by the library (structure_features), and by the offline CLI
// (`soiq features --format csv`). The three must agree: the server and the library bit for bit,
// the CLI to its 10 printed digits. A name the catalogue gains is covered without a change here.
#include "core/features/feature_catalogue.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/features/structure_features.h"
#include "core/geometry/primitives.h"
#include "core/io/read_image.h"
#include "core/io/read_mesh.h"
#include "core/voxelize/voxelize_1d.h"
#include "tests/integration/cohort.h"
#include "tests/integration/service_fixture.h"

namespace soiq::testing {
namespace {

// "name" for shape features, "name[region/image]" for intensity ones.
using Values = std::map<std::string, std::vector<double>>;

std::string key(const std::string& name, const std::string& region, const std::string& image) {
  return region.empty() ? name : name + "[" + region + "/" + image + "]";
}

// Every catalogue name once, with the mask surface's values beside the stored surface's.
std::vector<std::string> every_name() {
  std::vector<std::string> names;
  for (const FeatureDef& f : feature_catalogue()) {
    const std::string n(f.name);
    if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    if (f.family == FeatureFamily::kSurface) names.push_back(std::string(kMaskPrefix) + n);
  }
  return names;
}

// How many values a full report has: every catalogue entry (voxel_count twice: the structure's
// and the region's) and the mask_ variant of each surface feature.
size_t expected_count() {
  size_t n = 0;
  for (const FeatureDef& f : feature_catalogue()) n += f.family == FeatureFamily::kSurface ? 2 : 1;
  return n;
}

std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  EXPECT_EQ(pclose(pipe), 0) << command << "\n" << out;
  return out;
}

// `soiq features ... --format csv`: region,image,feature,value (arrays joined by ';').
Values parse_csv(const std::string& csv) {
  Values v;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (cells.size() != 4) continue;
    std::vector<double> numbers;
    std::stringstream parts(cells[3]);
    for (std::string p; std::getline(parts, p, ';');) numbers.push_back(std::stod(p));
    v[key(cells[2], cells[0], cells[1])] = numbers;
  }
  return v;
}

class FeatureCatalogueTest : public ServiceTest {};

TEST_F(FeatureCatalogueTest, EveryFeatureIsTheSameFromTheServerTheLibraryAndTheCli) {
  Cohort cohort = load_cohort(*this, *client_, dir_, 1);
  ASSERT_FALSE(cohort.structures.empty());
  const CohortStructure& s = cohort.structures.front();
  const std::string image_path = s.image_path;
  const std::vector<std::string> names = every_name();

  // The server, on the grid of the study's MR series: the image shares the structure's grid, so
  // centre_of_mass_shift_mm is defined too.
  v1::FeaturesRequest req;
  req.set_structure_id(s.id);
  req.mutable_grid()->set_series_modality("MR");
  for (const std::string& n : names) req.add_features(n);
  req.add_regions("inside");
  req.add_images("MR");
  Result<v1::FeaturesResponse> served = client_->compute_features(req);
  ASSERT_TRUE(served.ok()) << served.status().to_string();
  Values server;
  for (const v1::FeatureValue& f : served->features())
    server[key(f.name(), f.region(), f.region().empty() ? "" : "MR")] = {f.value().begin(), f.value().end()};

  // The library, on the image's grid.
  Result<TriangleMesh> mesh = read_mesh(s.mesh_path);
  ASSERT_TRUE(mesh.ok());
  Result<Image> image = read_image(image_path);
  ASSERT_TRUE(image.ok());
  Result<Voxelization> v = voxelize_1d(*mesh, image->geometry);
  ASSERT_TRUE(v.ok());
  FeatureRequest request;
  request.names = names;
  request.images.push_back({"MR", &*image});
  Result<FeatureReport> report = structure_features({v->volume, std::make_shared<const TriangleMesh>(*mesh)}, request);
  ASSERT_TRUE(report.ok()) << report.status().to_string();
  Values library;
  for (const Feature& f : report->features) library[key(f.name, f.region, f.image)] = f.value;

  // The CLI, offline, on the same image as reference grid.
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ",") + n;
  const Values cli = parse_csv(run(std::string(SOIQ_BINARY) + " features " + s.mesh_path + " --reference " +
                                   image_path + " --image MR=" + image_path + " --features " + list + " --format csv"));

  ASSERT_EQ(library.size(), expected_count());
  EXPECT_EQ(server.size(), library.size());
  EXPECT_EQ(cli.size(), library.size());
  for (const auto& [k, value] : library) {
    ASSERT_TRUE(server.count(k)) << k << " missing from the server's answer";
    EXPECT_EQ(server.at(k), value) << k;  // bitwise
    ASSERT_TRUE(cli.count(k)) << k << " missing from the CLI's output";
    ASSERT_EQ(cli.at(k).size(), value.size()) << k;
    for (size_t i = 0; i < value.size(); ++i)
      EXPECT_NEAR(cli.at(k)[i], value[i], 1e-9 * std::max(1.0, std::fabs(value[i]))) << k;
  }

  // A query reaches both voxel counts: the structure's, and with an image the region's samples.
  v1::QueryRequest q;
  q.mutable_stage1()->set_patient_id_glob(s.patient);
  q.mutable_grid()->set_series_modality("MR");
  q.add_select()->set_name("voxel_count");
  v1::FeatureRef* samples = q.add_select();
  samples->set_name("voxel_count");
  samples->set_region("inside");
  samples->set_image("MR");
  std::vector<v1::QueryRow> rows;
  client::QueryHandlers h;
  h.on_row = [&](const v1::QueryRow& row) {
    rows.push_back(row);
    return true;
  };
  Result<v1::QuerySummary> summary = client_->query(q, h);
  ASSERT_TRUE(summary.ok()) << summary.status().to_string();
  bool found = false;
  for (const v1::QueryRow& row : rows) {
    if (row.structure().id() != s.id) continue;
    found = true;
    ASSERT_EQ(row.values_size(), 2);
    EXPECT_EQ(row.values(0).value(0), library.at("voxel_count")[0]);
    EXPECT_EQ(row.values(1).value(0), library.at("voxel_count[inside/MR]")[0]);
    EXPECT_EQ(row.values(1).region(), "inside");
  }
  EXPECT_TRUE(found);
}

TEST_F(FeatureCatalogueTest, AMaskNameOfANonSurfaceFeatureIsRefusedBeforeAnyWork) {
  // mask_voxel_count once passed the name check and then failed on every structure of a query.
  Result<v1::UploadSurfaceResponse> up = upload(uv_sphere({0, 0, 0}, 10, 12, 24), "P", "S", "ball");
  ASSERT_TRUE(up.ok()) << up.status().to_string();
  v1::FeaturesRequest req;
  req.set_structure_id(up->structure().id());
  req.add_features("mask_voxel_count");
  Result<v1::FeaturesResponse> r = client_->compute_features(req);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  EXPECT_NE(r.status().message().find("unknown feature 'mask_voxel_count'"), std::string::npos) << r.status().message();

  v1::QueryRequest q;
  q.add_select()->set_name("mask_voxel_count");
  Result<v1::QuerySummary> s = client_->query(q, client::QueryHandlers{});
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), StatusCode::kInvalidArgument) << s.status().to_string();
  EXPECT_NE(s.status().message().find("unknown feature 'mask_voxel_count'"), std::string::npos) << s.status().message();

  // Its surface feature's mask value is served.
  req.clear_features();
  req.add_features("mask_sphericity");
  EXPECT_TRUE(client_->compute_features(req).ok());
}

}  // namespace
}  // namespace soiq::testing
