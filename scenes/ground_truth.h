#pragma once
// The ray-traced ground truth: Embree 3 shoots stratified jittered primary rays through every
// pixel of the camera's D3D screen, shades each hit with the one shading model (shading.h) and
// box-filters per pixel; alongside the colour it keeps per-pixel coverage and an edge mask for the
// metrics. Renders are cached on disk under a content hash of everything that changes the image.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace scenes {

// The raster frame's clear colour (sim::FrameSettings::clearColour; scenes/ cannot see sim/),
// so background pixels of the two images agree by default.
inline constexpr glm::vec3 kDefaultGroundTruthClearColour{0.05f, 0.05f, 0.08f};
inline constexpr int kDefaultGroundTruthSamples = 256;

struct GroundTruthSettings {
  int width = 1920;
  int height = 1080;
  // A perfect square n * n: one jittered sample in each cell of an n x n grid over the pixel.
  int samplesPerPixel = kDefaultGroundTruthSamples;
  glm::vec3 clearColour = kDefaultGroundTruthClearColour;
};

// Row-major, top row first, width * height entries each.
struct GroundTruthImage {
  int width = 0;
  int height = 0;
  int samplesPerPixel = 0;
  std::vector<glm::vec3> colour;   // linear RGB, the box-filtered mean of the samples
  std::vector<float> coverage;     // fraction of the samples that hit any triangle
  // 1 where the samples did not all see the same primitive (a triangle, or the background
  // counting as one more): the pixels an edge or a silhouette crosses. 0 elsewhere.
  std::vector<std::uint8_t> edge;

  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  }
};

// Called with the fraction of pixels done, non-decreasing, ending with exactly 1.0. Calls come
// from worker threads but never overlap (the renderer serialises them), so a callback needs no
// locking of its own.
using ProgressCallback = std::function<void(double fraction)>;

// Renders `scene` seen from `camera` (not scene.camera, so camera paths can pass their frames).
// Results do not depend on the number of threads. Throws std::invalid_argument (one line) for a
// non-positive or oversized width/height, a sample count that is not a perfect square in
// [1, 65536] or a degenerate camera; SceneError for out-of-range indices or attribute arrays that
// do not match the positions; std::runtime_error if Embree reports an error.
GroundTruthImage RenderGroundTruth(const Scene& scene, const Camera& camera,
                                   const GroundTruthSettings& settings,
                                   const ProgressCallback& progress = {});

// Stable 64-bit FNV-1a hash of every input that changes the rendered image: mesh positions,
// normals, texcoords, indices and materials, the materials and textures, the lighting, the camera,
// the settings and the renderer's format version. Names, bounds, scene.camera and mesh motion
// (the renderer draws frame 0) do not enter it.
std::uint64_t GroundTruthKey(const Scene& scene, const Camera& camera,
                             const GroundTruthSettings& settings);

struct CachedGroundTruth {
  GroundTruthImage image;
  bool cacheHit = false;        // true when the image was read back instead of rendered
  std::filesystem::path file;   // where it lives (or would have been written)
};

// A directory of rendered ground truths, one file per GroundTruthKey. Files are written to a
// temporary name and renamed into place, so readers never see half a file; a file that fails its
// size, header, key or payload-hash check is reported on stderr in one line and rendered again.
class GroundTruthCache {
 public:
  explicit GroundTruthCache(std::filesystem::path directory);

  // ${XDG_CACHE_HOME:-$HOME/.cache}/aasim/ground-truth (XDG_CACHE_HOME only when absolute).
  // Throws std::runtime_error when neither variable gives a directory.
  static std::filesystem::path DefaultDirectory();

  const std::filesystem::path& Directory() const { return directory_; }
  std::filesystem::path FileFor(std::uint64_t key) const;

  // The cached image for these inputs, or a fresh render stored for next time. A cache that
  // cannot be written costs a one-line warning, not the render.
  CachedGroundTruth LoadOrRender(const Scene& scene, const Camera& camera,
                                 const GroundTruthSettings& settings,
                                 const ProgressCallback& progress = {}) const;

 private:
  std::filesystem::path directory_;
};

// A one-line progress bar on stderr ("LABEL [#####     ]  42%"), redrawn when the percentage
// changes and ended with a newline at 1.0. Empty (no bar) unless stderr is a terminal or `force`.
ProgressCallback StderrProgressBar(std::string label, bool force = false);

}  // namespace scenes
