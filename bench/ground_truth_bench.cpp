// Ground-truth benchmark: times scenes::RenderGroundTruth (BVH build, jittered rays, shading, box
// filter) on a real glTF scene at 1920x1080 and, as the yardstick, Embree alone tracing the same
// number of unshaded rays in the same packets; prints both in Mrays/s and checks that one thread
// and all threads give bit-identical images.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>
#include <embree3/rtcore.h>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>

#include "bench/bench_util.h"
#include "scenes/ground_truth.h"
#include "scenes/scene.h"

namespace {

struct BenchOptions {
  std::string scene = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  int width = 1920;
  int height = 1080;
  int samples = 16;
  int frames = 3;
  int threads = tbb::info::default_concurrency();
  std::string json;
};

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct EmbreeRelease {
  void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};

struct EmbreeTimes {
  double buildSeconds = 0.0;
  double traceSeconds = 0.0;
};

// Embree alone: the scene built as the ground truth builds it (robust triangles, one geometry per
// mesh), then width * height * samples rays through the strata centres of every pixel (the
// renderer's unprojection, no jitter), 16 consecutive samples per rtcIntersect16 packet, nothing
// shaded.
EmbreeTimes TimeEmbreeAlone(const scenes::Scene& scene, const BenchOptions& options) {
  EmbreeTimes times;
  const auto buildStart = std::chrono::steady_clock::now();
  const std::unique_ptr<std::remove_pointer_t<RTCDevice>, EmbreeRelease> device(rtcNewDevice(nullptr));
  const std::unique_ptr<std::remove_pointer_t<RTCScene>, EmbreeRelease> embree(rtcNewScene(device.get()));
  rtcSetSceneFlags(embree.get(), RTC_SCENE_FLAG_ROBUST);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    if (mesh.indices.size() < 3) continue;
    RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree-owned copies: they carry the tail padding Embree's vector loads need.
    std::memcpy(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3),
                                        mesh.positions.size()),
                mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
    std::memcpy(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(std::uint32_t), mesh.indices.size() / 3),
                mesh.indices.data(), mesh.indices.size() / 3 * 3 * sizeof(std::uint32_t));
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(embree.get(), geometry, static_cast<unsigned>(m));
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(embree.get());
  if (rtcGetDeviceError(device.get()) != RTC_ERROR_NONE) throw std::runtime_error("Embree failed to build the scene");
  times.buildSeconds = SecondsSince(buildStart);

  // The renderer's unprojection: double precision from the float view-projection matrix.
  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  const glm::dmat4 inverse = glm::inverse(glm::dmat4(scene.camera.Projection(aspect) * scene.camera.View()));
  const int strata = static_cast<int>(std::lround(std::sqrt(options.samples)));
  const auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<int>(0, options.height), [&](const tbb::blocked_range<int>& rows) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (int y = rows.begin(); y != rows.end(); ++y) {
      for (int x = 0; x < options.width; ++x) {
        for (int first = 0; first < options.samples; first += 16) {
          alignas(64) RTCRayHit16 packet;
          alignas(64) int valid[16];
          for (int lane = 0; lane < 16; ++lane) {
            const int sample = std::min(first + lane, options.samples - 1);
            valid[lane] = first + lane < options.samples ? -1 : 0;
            const double sx = x + (sample % strata + 0.5) / strata;
            const double sy = y + (sample / strata + 0.5) / strata;
            const double nx = 2.0 * sx / options.width - 1.0;
            const double ny = 1.0 - 2.0 * sy / options.height;
            const glm::dvec4 near = inverse * glm::dvec4(nx, ny, 0.0, 1.0);
            const glm::dvec4 far = inverse * glm::dvec4(nx, ny, 1.0, 1.0);
            const glm::dvec3 origin = glm::dvec3(near) * (1.0 / near.w);
            const glm::dvec3 direction = glm::dvec3(far) * (1.0 / far.w) - origin;
            packet.ray.org_x[lane] = static_cast<float>(origin.x);
            packet.ray.org_y[lane] = static_cast<float>(origin.y);
            packet.ray.org_z[lane] = static_cast<float>(origin.z);
            packet.ray.dir_x[lane] = static_cast<float>(direction.x);
            packet.ray.dir_y[lane] = static_cast<float>(direction.y);
            packet.ray.dir_z[lane] = static_cast<float>(direction.z);
            packet.ray.tnear[lane] = 0.0f;
            packet.ray.tfar[lane] = 1.0f;
            packet.ray.time[lane] = 0.0f;
            packet.ray.mask[lane] = ~0u;
            packet.ray.id[lane] = static_cast<unsigned>(lane);
            packet.ray.flags[lane] = 0;
            packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
          }
          rtcIntersect16(valid, embree.get(), &context, &packet);
        }
      }
    }
  });
  times.traceSeconds = SecondsSince(start);
  return times;
}

scenes::GroundTruthImage Render(const scenes::Scene& scene, const scenes::GroundTruthSettings& settings,
                                int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  return scenes::RenderGroundTruth(scene, scene.camera, settings);
}

bool SameImage(const scenes::GroundTruthImage& a, const scenes::GroundTruthImage& b) {
  return a.colour == b.colour && a.coverage == b.coverage && a.edge == b.edge;
}

int RunBench(const BenchOptions& options) {
  std::ofstream jsonFile;
  if (!options.json.empty()) {
    jsonFile.open(options.json);
    if (!jsonFile) throw std::runtime_error(options.json + ": cannot write JSON");
  }
  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  const scenes::Scene scene = scenes::LoadScene(options.scene, aspect);
  scenes::GroundTruthSettings settings;
  settings.width = options.width;
  settings.height = options.height;
  settings.samplesPerPixel = options.samples;
  const double rays = static_cast<double>(options.width) * options.height * options.samples;

  std::vector<double> renderSeconds, buildSeconds, traceSeconds;
  scenes::GroundTruthImage last;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(options.threads));
    for (int frame = 0; frame < options.frames; ++frame) {
      auto start = std::chrono::steady_clock::now();
      last = scenes::RenderGroundTruth(scene, scene.camera, settings);
      renderSeconds.push_back(SecondsSince(start));
      const EmbreeTimes embree = TimeEmbreeAlone(scene, options);
      buildSeconds.push_back(embree.buildSeconds);
      traceSeconds.push_back(embree.traceSeconds);
    }
  }
  const bool deterministic = SameImage(Render(scene, settings, 1), last);
  double covered = 0.0;
  std::size_t edges = 0;
  for (std::size_t i = 0; i < last.coverage.size(); ++i) {
    covered += static_cast<double>(last.coverage[i]);
    edges += last.edge[i];
  }
  const double renderMrays = rays / bench::Median(renderSeconds) / 1e6;
  const double traceMrays = rays / bench::Median(traceSeconds) / 1e6;
  std::printf("aasim ground-truth bench: %s (%zu triangles), %dx%d, %d samples per pixel, %d threads, median of %d\n",
              options.scene.c_str(), scene.TriangleCount(), options.width, options.height, options.samples,
              options.threads, options.frames);
  std::printf("  ground truth (build + rays + shading + filter): %8.3f s  %8.1f Mrays/s\n",
              bench::Median(renderSeconds), renderMrays);
  std::printf("  Embree alone (same rays and packets, unshaded): %8.3f s  %8.1f Mrays/s  (+ %.3f s BVH build)\n",
              bench::Median(traceSeconds), traceMrays, bench::Median(buildSeconds));
  std::printf("  covered %.1f%% of the image, %zu edge pixels\n", 100.0 * covered / static_cast<double>(last.coverage.size()),
              edges);
  std::printf("deterministic (1 vs %d threads): %s\n", options.threads, deterministic ? "yes" : "no");
  if (jsonFile.is_open()) {
    const nlohmann::ordered_json json = {{"schema", "aasim.bench.ground_truth"},
                                         {"version", 1},
                                         {"scene", options.scene},
                                         {"triangles", scene.TriangleCount()},
                                         {"width", options.width},
                                         {"height", options.height},
                                         {"samples_per_pixel", options.samples},
                                         {"threads", options.threads},
                                         {"frames", options.frames},
                                         {"render_seconds", renderSeconds},
                                         {"embree_only_seconds", traceSeconds},
                                         {"embree_build_seconds", buildSeconds},
                                         {"render_mrays_per_second", renderMrays},
                                         {"embree_only_mrays_per_second", traceMrays},
                                         {"deterministic", deterministic}};
    jsonFile << json.dump(2) << '\n';
    jsonFile.close();
    if (!jsonFile) throw std::runtime_error(options.json + ": cannot write JSON");
  }
  return deterministic ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Ground-truth benchmark: Embree renders of a scene in Mrays/s, next to Embree alone on the same "
      "rays; exits 1 unless 1 thread and all threads give bit-identical images",
      "aasim_ground_truth_bench"};
  BenchOptions options;
  app.add_option("--scene", options.scene, "glTF file or builtin:NAME")->type_name("FILE|builtin:NAME")->capture_default_str();
  app.add_option("--width", options.width, "Image width")->check(CLI::Range(1, 32768))->capture_default_str();
  app.add_option("--height", options.height, "Image height")->check(CLI::Range(1, 32768))->capture_default_str();
  app.add_option("--spp", options.samples, "Samples per pixel, a perfect square")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  app.add_option("--frames", options.frames, "Timed renders")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--threads", options.threads, "Worker threads for the timed renders [default: all cores]")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app.add_option("--json", options.json, "Also write the results as JSON to FILE")->type_name("FILE");
  return bench::ParseAndRun(app, argc, argv, [&] { return RunBench(options); });
}
