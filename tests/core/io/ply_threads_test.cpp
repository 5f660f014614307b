// PLY files read and written from many threads at once (soiqd reads uploads on many threads; the
// query benchmark writes its cohort on several): VTK's PLY code keeps static state, so without
// core/io/vtk_ply_lock.h this corrupts the heap and crashes.

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "core/geometry/primitives.h"
#include "core/io/read_mesh.h"
#include "core/io/write_mesh.h"

namespace soiq {
namespace {

TEST(PlyThreads, ManyThreadsReadAndWritePlyFilesAtOnce) {
  const std::string dir = (std::filesystem::temp_directory_path() / "soiq-ply-threads").string();
  std::filesystem::create_directories(dir);
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&, t] {
      const TriangleMesh m = uv_sphere({0, 0, 0}, 5 + t, 16 + t, 32);
      for (int i = 0; i < 15; ++i) {
        const std::string path = dir + "/t" + std::to_string(t) + "_" + std::to_string(i) + ".ply";
        if (!write_mesh(m, path).ok()) ++failures;
        Result<TriangleMesh> back = read_mesh(path);
        if (!back.ok() || back->triangles.size() != m.triangles.size() ||
            back->vertices_mm.size() != m.vertices_mm.size())
          ++failures;
      }
    });
  }
  for (auto& th : threads) th.join();
  std::filesystem::remove_all(dir);
  EXPECT_EQ(failures.load(), 0);
}

}  // namespace
}  // namespace soiq
