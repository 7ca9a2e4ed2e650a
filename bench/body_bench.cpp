// Building the male legs body (read, validate, remesh, tetrahedralize, pin the core) at
// 15 mm and 10 mm edge length: wall time, tet counts and peak memory. ScanBody builds
// it from a scan of about a million triangles made at run time (scan_repair.hpp).
//
// Peak memory is getrusage's ru_maxrss, the peak of the whole process so far: run one
// size per process for a clean number, e.g.
//   body_bench --benchmark_filter='LegsBody/15'
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <random>
#include <unordered_map>

#include "tightfit/body/body_spec.hpp"
#include "tightfit/body/scan_import.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/geometry/mesh_measures.hpp"

namespace {

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void LegsBody(benchmark::State& state) {
  const double edge = static_cast<double>(state.range(0)) * 1e-3;
  const tightfit::BodySpec spec = tightfit::parse_body_spec(
      nlohmann::json{{"mesh", TIGHTFIT_DATA_DIR "/bodies/mh_legs_male.obj"}, {"edge_length", edge}},
      "", ".", "bench");
  tightfit::Body body;
  tightfit::BuildReport report;
  for (auto _ : state) {
    report = tightfit::BuildReport();
    body = tightfit::build_body(spec, &report);
    benchmark::DoNotOptimize(body.volume.tets.data());
  }
  state.counters["surface_vertices"] = body.num_surface_vertices();
  state.counters["volume_vertices"] = body.num_vertices();
  state.counters["tets"] = body.volume.num_tets();
  state.counters["pinned"] = static_cast<double>(body.pinned.size());
  for (const auto& [stage, seconds] : report.stage_seconds) state.counters[stage + "_s"] = seconds;
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

BENCHMARK(LegsBody)->Arg(15)->Arg(10)->Unit(benchmark::kSecond)->Iterations(3);

/// Every triangle of `mesh` split into n² by cutting each edge into n pieces (vertices
/// on the input's edges shared between its two faces).
tightfit::TriMesh split_edges(const tightfit::TriMesh& mesh, int n) {
  const int m = mesh.num_faces(), nv = mesh.num_vertices();
  std::vector<tightfit::Vec3> points;
  for (int v = 0; v < nv; ++v) points.emplace_back(mesh.vertices.row(v));
  std::unordered_map<std::uint64_t, int> edge_start;  // first of the n-1 points from min to max
  auto edge_point = [&](int a, int b, int k) {        // point k of n along a → b
    if (k == 0) return a;
    if (k == n) return b;
    const int lo = std::min(a, b), hi = std::max(a, b);
    const std::uint64_t key = static_cast<std::uint64_t>(lo) * static_cast<std::uint64_t>(nv) + hi;
    auto [it, added] = edge_start.try_emplace(key, static_cast<int>(points.size()));
    if (added)
      for (int j = 1; j < n; ++j)
        points.push_back(((n - j) * tightfit::Vec3(mesh.vertices.row(lo)) +
                          j * tightfit::Vec3(mesh.vertices.row(hi))) /
                         n);
    return it->second + (a == lo ? k : n - k) - 1;
  };
  std::vector<Eigen::Vector3i> faces;
  faces.reserve(static_cast<std::size_t>(m) * n * n);
  std::vector<int> grid((n + 1) * (n + 2) / 2);
  for (int f = 0; f < m; ++f) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    auto id = [n](int i, int j) {
      return i * (n + 1) - i * (i - 1) / 2 + j;
    };  // i steps a → c, j a → b
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        int v;
        if (i == 0)
          v = edge_point(a, b, j);
        else if (j == 0)
          v = edge_point(a, c, i);
        else if (i + j == n)
          v = edge_point(b, c, i);
        else {
          v = static_cast<int>(points.size());
          points.push_back(((n - i - j) * tightfit::Vec3(mesh.vertices.row(a)) +
                            j * tightfit::Vec3(mesh.vertices.row(b)) +
                            i * tightfit::Vec3(mesh.vertices.row(c))) /
                           n);
        }
        grid[id(i, j)] = v;
      }
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        faces.emplace_back(grid[id(i, j)], grid[id(i, j + 1)], grid[id(i + 1, j)]);
        if (i + j + 1 < n)
          faces.emplace_back(grid[id(i, j + 1)], grid[id(i + 1, j + 1)], grid[id(i + 1, j)]);
      }
  }
  tightfit::TriMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v)
    out.vertices.row(static_cast<Eigen::Index>(v)) = points[v];
  out.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    out.faces.row(static_cast<Eigen::Index>(f)) = faces[f];
  return out;
}

/// A scan of the legs: 144 triangles per triangle of the shared mesh (1.1 M), up to
/// 0.1 mm of noise along the normals, three holes of about 2 cm across on the left leg.
tightfit::TriMesh legs_scan() {
  tightfit::TriMesh scan = split_edges(
      tightfit::read_tri_mesh(std::filesystem::path(TIGHTFIT_DATA_DIR) / "bodies/mh_legs_male.obj"),
      12);
  // Noise of 0.1 mm, less where a tenth of a face's height is smaller (the thin faces
  // of the shared mesh's flat caps would fold over).
  const tightfit::Points3 normals = tightfit::vertex_normals(scan);
  const tightfit::VecX areas = tightfit::face_areas(scan);
  tightfit::VecX amplitude = tightfit::VecX::Constant(scan.vertices.rows(), 1e-4);
  for (Eigen::Index f = 0; f < scan.faces.rows(); ++f) {
    double longest = 0.0;
    for (int c = 0; c < 3; ++c)
      longest = std::max(longest, (scan.vertices.row(scan.faces(f, c)) -
                                   scan.vertices.row(scan.faces(f, (c + 1) % 3)))
                                      .norm());
    for (int c = 0; c < 3; ++c)
      amplitude(scan.faces(f, c)) =
          std::min(amplitude(scan.faces(f, c)), 0.1 * 2.0 * areas(f) / longest);
  }
  std::mt19937 random(13);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (Eigen::Index v = 0; v < scan.vertices.rows(); ++v)
    scan.vertices.row(v) += amplitude(v) * noise(random) * normals.row(v);
  std::vector<tightfit::Vec3> holes;
  for (const double height : {0.3, 0.6, 0.85}) {
    Eigen::Index front = -1;
    for (Eigen::Index v = 0; v < scan.vertices.rows(); ++v)
      if (scan.vertices(v, 0) > 0.05 && std::abs(scan.vertices(v, 1) - height) < 0.01 &&
          (front < 0 || scan.vertices(v, 2) > scan.vertices(front, 2)))
        front = v;
    holes.emplace_back(scan.vertices.row(front));
  }
  Eigen::Index kept = 0;
  for (Eigen::Index f = 0; f < scan.faces.rows(); ++f) {
    bool keep = true;
    for (int c = 0; c < 3; ++c)
      for (const tightfit::Vec3& h : holes)
        keep = keep && (tightfit::Vec3(scan.vertices.row(scan.faces(f, c))) - h).norm() > 0.01;
    if (keep) scan.faces.row(kept++) = scan.faces.row(f);
  }
  scan.faces.conservativeResize(kept, 3);
  return scan;
}

/// The legs body at 15 mm from a file of about a million triangles (binary PLY): read,
/// repair, fill the holes, validate, remesh (straight from the million triangles),
/// tetrahedralize. Counters: the scan's size, reading the file (`parse_s`) and
/// import_scan (`import_s`: repair, holes, units) timed apart once before the timed
/// build, the build's stages (its `read` holds both and the validation), and the peak
/// RSS (the process's: run it alone, --benchmark_filter=ScanBody; `scan_peak_rss_MB`
/// is the part of making the scan).
void ScanBody(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tightfit_scan_bench_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "legs_scan.ply";
  {
    const tightfit::TriMesh scan = legs_scan();
    state.counters["scan_faces"] = static_cast<double>(scan.num_faces());
    tightfit::write_tri_mesh(file, scan);
  }
  state.counters["scan_peak_rss_MB"] = peak_rss_mb();
  auto start = Clock::now();
  const tightfit::TriMesh read = tightfit::read_tri_mesh(file);
  state.counters["parse_s"] = std::chrono::duration<double>(Clock::now() - start).count();
  start = Clock::now();
  std::vector<std::string> warnings;
  const tightfit::TriMesh imported = tightfit::import_scan(read, file.string(), 0.0, warnings);
  state.counters["import_s"] = std::chrono::duration<double>(Clock::now() - start).count();
  state.counters["imported_faces"] = static_cast<double>(imported.num_faces());
  const tightfit::BodySpec spec = tightfit::parse_body_spec(
      nlohmann::json{{"mesh", file.string()}, {"edge_length", 0.015}}, "", ".", "bench");
  tightfit::Body body;
  tightfit::BuildReport report;
  for (auto _ : state) {
    report = tightfit::BuildReport();
    body = tightfit::build_body(spec, &report);
    benchmark::DoNotOptimize(body.volume.tets.data());
  }
  std::filesystem::remove_all(dir);
  state.counters["surface_vertices"] = body.num_surface_vertices();
  state.counters["tets"] = body.volume.num_tets();
  for (const auto& [stage, seconds] : report.stage_seconds) state.counters[stage + "_s"] = seconds;
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

BENCHMARK(ScanBody)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

#include "bench_main.hpp"
