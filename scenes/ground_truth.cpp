// The Embree ground truth and its on-disk cache (see ground_truth.h). Rays are traced in packets
// of 16 consecutive samples of a tile's pixel stream, so a packet usually stays inside one pixel
// and Embree's coherent packet traversal does the work.

#include "scenes/ground_truth.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "scenes/normals.h"
#include "scenes/shading.h"

namespace scenes {
namespace {

// Bump whenever the renderer's output changes for the same inputs (sampling, shading, file
// layout): old cache files then miss instead of being trusted.
constexpr std::uint32_t kFormatVersion = 1;
constexpr int kMaxSamplesPerPixel = 65536;
constexpr int kMaxDimension = 32768;
// Tiles are the unit of parallel work and of progress: 256 pixels, enough rays per task to hide
// scheduling at any sample count.
constexpr int kTileSize = 16;
constexpr int kPacketSize = 16;
constexpr std::uint64_t kSamplingSeed = 0x6161'7369'6d47'5431ULL;  // "aasimGT1"
constexpr std::uint64_t kBackgroundId = ~std::uint64_t{0};

// ---------------------------------------------------------------------------------------------
// Input checks

std::string ErrorPrefix() { return "ground truth: "; }

int StrataPerSide(int samplesPerPixel) {
  const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(samplesPerPixel))));
  return side * side == samplesPerPixel ? side : 0;
}

glm::mat4 ViewProjection(const Camera& camera, int width, int height) {
  // The float product ToClipSpace feeds the rasterizer, so rays see what raster/ sees.
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  return camera.Projection(aspect) * camera.View();
}

void ValidateSettings(const Camera& camera, const GroundTruthSettings& settings) {
  auto fail = [](const std::string& problem) { throw std::invalid_argument(ErrorPrefix() + problem); };
  if (settings.width < 1 || settings.width > kMaxDimension || settings.height < 1 ||
      settings.height > kMaxDimension) {
    fail("image size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
         " is outside 1.." + std::to_string(kMaxDimension));
  }
  if (settings.samplesPerPixel < 1 || settings.samplesPerPixel > kMaxSamplesPerPixel ||
      StrataPerSide(settings.samplesPerPixel) == 0) {
    fail("samples per pixel must be a perfect square (n x n strata) in 1.." +
         std::to_string(kMaxSamplesPerPixel) + ", got " + std::to_string(settings.samplesPerPixel));
  }
  if (!(camera.verticalFovRadians > 0.0f && camera.verticalFovRadians < std::numbers::pi_v<float>) ||
      !(camera.zNear > 0.0f && camera.zFar > camera.zNear) || !std::isfinite(camera.zFar)) {
    fail("camera needs 0 < field of view < pi and 0 < zNear < zFar < inf");
  }
  const glm::dmat4 inverse = glm::inverse(glm::dmat4(ViewProjection(camera, settings.width, settings.height)));
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(inverse[c][r])) fail("the camera's view-projection matrix is not invertible");
    }
  }
}

void ValidateScene(const Scene& scene) {
  auto fail = [&](const std::string& problem) { throw SceneError(scene.name + ": " + problem); };
  for (const Texture& texture : scene.textures) {
    if (texture.width < 1 || texture.height < 1 ||
        texture.texels.size() != static_cast<std::size_t>(texture.width) * static_cast<std::size_t>(texture.height)) {
      fail("texture '" + texture.name + "' has " + std::to_string(texture.texels.size()) + " texels for " +
           std::to_string(texture.width) + "x" + std::to_string(texture.height));
    }
  }
  for (const Material& material : scene.materials) {
    if (material.baseColourTexture >= static_cast<int>(scene.textures.size())) {
      fail("material '" + material.name + "' names texture " + std::to_string(material.baseColourTexture) +
           " of " + std::to_string(scene.textures.size()));
    }
  }
  for (const Mesh& mesh : scene.meshes) {
    const std::string where = "mesh '" + mesh.name + "': ";
    const std::size_t vertices = mesh.positions.size();
    if (!mesh.normals.empty() && mesh.normals.size() != vertices) {
      fail(where + std::to_string(mesh.normals.size()) + " normals for " + std::to_string(vertices) + " vertices");
    }
    if (!mesh.texcoords.empty() && mesh.texcoords.size() != vertices) {
      fail(where + std::to_string(mesh.texcoords.size()) + " texcoords for " + std::to_string(vertices) +
           " vertices");
    }
    if (mesh.material >= static_cast<int>(scene.materials.size())) {
      fail(where + "material " + std::to_string(mesh.material) + " of " + std::to_string(scene.materials.size()));
    }
    for (const std::uint32_t index : mesh.indices) {
      if (index >= vertices) {
        fail(where + "index " + std::to_string(index) + " out of range (" + std::to_string(vertices) + " vertices)");
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Embree scene

struct DeviceRelease {
  void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
};
struct SceneRelease {
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};
using DeviceHandle = std::unique_ptr<std::remove_pointer_t<RTCDevice>, DeviceRelease>;
using SceneHandle = std::unique_ptr<std::remove_pointer_t<RTCScene>, SceneRelease>;

// Embree reports errors through a callback that may run on its worker threads; the first one is
// kept and rethrown on the calling thread, since exceptions must not cross Embree's C frames.
struct EmbreeErrors {
  std::mutex mutex;
  std::string first;

  static void Record(void* self, RTCError code, const char* message) {
    auto* errors = static_cast<EmbreeErrors*>(self);
    const std::lock_guard lock(errors->mutex);
    if (errors->first.empty()) {
      errors->first = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
    }
  }
  void ThrowIfAny() {
    const std::lock_guard lock(mutex);
    if (!first.empty()) throw std::runtime_error(ErrorPrefix() + first);
  }
};

// One Embree triangle geometry per mesh with geometry id = mesh index, so a hit names its mesh.
// Robust mode: the default trades arithmetic accuracy for speed, and a ray through the shared
// edge of two triangles can then miss both, which here would be a false background sample and a
// false edge pixel; robust traversal costs about 15% on 2CylinderEngine.
SceneHandle BuildEmbreeScene(RTCDevice device, const Scene& scene) {
  SceneHandle handle(rtcNewScene(device));
  rtcSetSceneFlags(handle.get(), RTC_SCENE_FLAG_ROBUST);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const std::size_t triangles = mesh.indices.size() / 3;
    if (triangles == 0) continue;
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Copied into Embree-owned buffers, which carry the tail padding Embree's vector loads need.
    void* vertices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                             sizeof(glm::vec3), mesh.positions.size());
    void* indices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                            3 * sizeof(std::uint32_t), triangles);
    if (vertices != nullptr && indices != nullptr) {
      std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
      std::memcpy(indices, mesh.indices.data(), triangles * 3 * sizeof(std::uint32_t));
      rtcCommitGeometry(geometry);
      rtcAttachGeometryByID(handle.get(), geometry, static_cast<unsigned>(m));
    }
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(handle.get());
  return handle;
}

// ---------------------------------------------------------------------------------------------
// Sampling

// SplitMix64 (Steele, Lea, Flood 2014): a counter through a 64-bit finaliser; cheap, and every
// pixel gets an independent stream from its index alone, whatever thread renders it.
class PixelRng {
 public:
  explicit PixelRng(std::uint64_t pixelIndex) : state_(Mix(kSamplingSeed ^ Mix(pixelIndex))) {}
  // Two independent 24-bit uniforms in [0, 1) from one draw.
  glm::vec2 Jitter() {
    state_ += kGamma;
    const std::uint64_t bits = Mix(state_);
    constexpr float kScale = 1.0f / 16777216.0f;
    return {static_cast<float>(bits >> 40) * kScale, static_cast<float>((bits >> 16) & 0xFFFFFFu) * kScale};
  }

 private:
  static constexpr std::uint64_t kGamma = 0x9E3779B97F4A7C15ULL;
  static std::uint64_t Mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

// Screen position (D3D: +y down, pixel centres at +0.5) -> the segment between the near and far
// planes through it, by unprojecting NDC z = 0 and z = 1 through inverse(Projection * View). The
// homogeneous points are affine in the screen position, so only the divide is per ray; double
// precision keeps far-plane points of deep frusta exact to float.
class RayGenerator {
 public:
  RayGenerator(const Camera& camera, int width, int height) {
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(ViewProjection(camera, width, height)));
    // ndc.x = 2 sx / width - 1, ndc.y = 1 - 2 sy / height.
    perX_ = inverse[0] * (2.0 / static_cast<double>(width));
    perY_ = inverse[1] * (-2.0 / static_cast<double>(height));
    nearAtOrigin_ = inverse[3] - inverse[0] + inverse[1];
    nearToFar_ = inverse[2];
  }

  // Fills all 16 lanes from their screen positions; lanes at or past `active` get an empty
  // segment (Embree skips them, but nothing it reads is left undefined). One straight loop over
  // plain arrays, so the compiler vectorises it.
  void Fill(RTCRayHit16& packet, const std::array<double, kPacketSize>& sx, const std::array<double, kPacketSize>& sy,
            int active) const {
    for (int lane = 0; lane < kPacketSize; ++lane) {
      const auto slot = static_cast<std::size_t>(lane);
      const double x = sx[slot], y = sy[slot];
      const double nearX = nearAtOrigin_.x + perX_.x * x + perY_.x * y;
      const double nearY = nearAtOrigin_.y + perX_.y * x + perY_.y * y;
      const double nearZ = nearAtOrigin_.z + perX_.z * x + perY_.z * y;
      const double nearW = nearAtOrigin_.w + perX_.w * x + perY_.w * y;
      // One reciprocal per point instead of three divides: divides dominated ray generation.
      const double toNear = 1.0 / nearW;
      const double toFar = 1.0 / (nearW + nearToFar_.w);
      const double originX = nearX * toNear, originY = nearY * toNear, originZ = nearZ * toNear;
      packet.ray.org_x[lane] = static_cast<float>(originX);
      packet.ray.org_y[lane] = static_cast<float>(originY);
      packet.ray.org_z[lane] = static_cast<float>(originZ);
      packet.ray.dir_x[lane] = static_cast<float>((nearX + nearToFar_.x) * toFar - originX);
      packet.ray.dir_y[lane] = static_cast<float>((nearY + nearToFar_.y) * toFar - originY);
      packet.ray.dir_z[lane] = static_cast<float>((nearZ + nearToFar_.z) * toFar - originZ);
      packet.ray.tnear[lane] = 0.0f;                      // the near plane: the rasterizer clips there too
      packet.ray.tfar[lane] = lane < active ? 1.0f : 0.0f;  // the far plane
      packet.ray.time[lane] = 0.0f;
      packet.ray.mask[lane] = ~0u;
      packet.ray.id[lane] = static_cast<unsigned>(lane);
      packet.ray.flags[lane] = 0;
      packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
    }
  }

 private:
  glm::dvec4 perX_, perY_, nearAtOrigin_, nearToFar_;
};

// ---------------------------------------------------------------------------------------------
// Shading

// What the shader reads per hit, gathered once per render.
struct ShadedMesh {
  std::vector<glm::vec3> normals;  // VertexNormals: the mesh's, else smooth
  const glm::vec2* texcoords = nullptr;
  const std::uint32_t* indices = nullptr;
  bool textured = false;
  glm::vec3 untexturedBase{0.0f};  // BaseColour when no texture makes it depend on uv
};

std::vector<ShadedMesh> PrepareMeshes(const Scene& scene) {
  std::vector<ShadedMesh> meshes(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    ShadedMesh& shaded = meshes[m];
    shaded.normals = VertexNormals(mesh);
    shaded.texcoords = mesh.texcoords.empty() ? nullptr : mesh.texcoords.data();
    shaded.indices = mesh.indices.data();
    shaded.textured = mesh.material >= 0 &&
                      scene.materials[static_cast<std::size_t>(mesh.material)].baseColourTexture >= 0;
    shaded.untexturedBase = glm::vec3(BaseColour(scene, m, glm::vec2(0.0f)));
  }
  return meshes;
}

struct RenderContext {
  const Scene& scene;
  const GroundTruthSettings& settings;
  RTCScene embree;
  const std::vector<ShadedMesh>& meshes;
  RayGenerator rays;
  int strata;
};

// The raster material kernel's function (sim/frame.cpp) at one hit: the interpolated vertex
// normal, normalised, negated on a triangle seen from behind, lit by ShadeLambert.
glm::vec3 ShadeHit(const RenderContext& context, const RTCRayHit16& packet, int lane) {
  const ShadedMesh& mesh = context.meshes[packet.hit.geomID[lane]];
  const std::uint32_t* corners = mesh.indices + 3 * std::size_t{packet.hit.primID[lane]};
  const float u = packet.hit.u[lane], v = packet.hit.v[lane];
  const float w = 1.0f - u - v;
  glm::vec3 normal = mesh.normals[corners[0]] * w + mesh.normals[corners[1]] * u + mesh.normals[corners[2]] * v;
  const glm::vec3 geometric{packet.hit.Ng_x[lane], packet.hit.Ng_y[lane], packet.hit.Ng_z[lane]};
  // Opposite vertex normals can cancel; the face normal keeps such a sample finite.
  normal = glm::dot(normal, normal) > 0.0f ? glm::normalize(normal) : glm::normalize(geometric);
  // Embree's Ng points out of the counter-clockwise (front) face, the raster's front face; a
  // triangle whose front faces away from the ray is the raster's back-facing triangle.
  const glm::vec3 direction{packet.ray.dir_x[lane], packet.ray.dir_y[lane], packet.ray.dir_z[lane]};
  if (glm::dot(geometric, direction) > 0.0f) normal = -normal;
  glm::vec3 base = mesh.untexturedBase;
  if (mesh.textured) {
    glm::vec2 uv(0.0f);
    if (mesh.texcoords != nullptr) {
      uv = mesh.texcoords[corners[0]] * w + mesh.texcoords[corners[1]] * u + mesh.texcoords[corners[2]] * v;
    }
    base = glm::vec3(BaseColour(context.scene, packet.hit.geomID[lane], uv));
  }
  return ShadeLambert(context.scene.lighting, base, normal);
}

// The running sums of the pixel whose samples are being traced.
struct PixelSum {
  glm::dvec3 colour{0.0};
  std::uint32_t hits = 0;
  std::uint64_t firstId = 0;
  bool mixed = false;
};

// Renders one tile. Its pixels' samples form one stream (pixel by pixel, each pixel's n x n
// strata row by row) cut into packets of 16, and each pixel's samples are summed in stream
// order, so the output depends on neither the packet boundaries nor the thread. The stream's
// cursor advances by increments because integer divides per ray showed up in profiles.
void RenderTile(const RenderContext& context, int tileX, int tileY, GroundTruthImage& image) {
  const int x0 = tileX * kTileSize, y0 = tileY * kTileSize;
  const int x1 = std::min(x0 + kTileSize, image.width);
  const int y1 = std::min(y0 + kTileSize, image.height);
  const int samples = context.settings.samplesPerPixel;
  const int strata = context.strata;
  const double strataScale = 1.0 / strata;
  const std::int64_t total = std::int64_t{x1 - x0} * (y1 - y0) * samples;

  RTCIntersectContext intersect;
  rtcInitIntersectContext(&intersect);
  intersect.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;

  // Where the next sample comes from: pixel (px, py), stratum (i, j).
  int px = x0, py = y0, i = 0, j = 0;
  PixelRng rng(image.Index(px, py));
  std::array<std::size_t, kPacketSize> lanePixel{};
  std::array<bool, kPacketSize> laneFirst{}, laneLast{};
  PixelSum sum;
  for (std::int64_t start = 0; start < total; start += kPacketSize) {
    alignas(64) RTCRayHit16 packet;
    alignas(64) std::array<int, kPacketSize> valid{};
    const int lanes = static_cast<int>(std::min<std::int64_t>(kPacketSize, total - start));
    alignas(64) std::array<double, kPacketSize> sx{}, sy{};
    for (int lane = 0; lane < lanes; ++lane) {
      const glm::vec2 jitter = rng.Jitter();
      const auto slot = static_cast<std::size_t>(lane);
      sx[slot] = px + (i + static_cast<double>(jitter.x)) * strataScale;
      sy[slot] = py + (j + static_cast<double>(jitter.y)) * strataScale;
      valid[slot] = -1;
      lanePixel[slot] = image.Index(px, py);
      laneFirst[slot] = i == 0 && j == 0;
      laneLast[slot] = false;
      if (++i < strata) continue;
      i = 0;
      if (++j < strata) continue;
      j = 0;
      laneLast[slot] = true;
      if (++px == x1) {
        px = x0;
        ++py;
      }
      if (py < y1) rng = PixelRng(image.Index(px, py));
    }
    context.rays.Fill(packet, sx, sy, lanes);
    rtcIntersect16(valid.data(), context.embree, &intersect, &packet);
    for (int lane = 0; lane < lanes; ++lane) {
      const auto slot = static_cast<std::size_t>(lane);
      std::uint64_t id = kBackgroundId;
      glm::vec3 colour = context.settings.clearColour;
      if (packet.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID) {
        id = (std::uint64_t{packet.hit.geomID[lane]} << 32) | packet.hit.primID[lane];
        colour = ShadeHit(context, packet, lane);
      }
      if (laneFirst[slot]) {
        sum = PixelSum{};
        sum.firstId = id;
      } else if (id != sum.firstId) {
        sum.mixed = true;
      }
      sum.colour += glm::dvec3(colour);
      sum.hits += id != kBackgroundId ? 1 : 0;
      if (laneLast[slot]) {
        const std::size_t index = lanePixel[slot];
        image.colour[index] = glm::vec3(sum.colour / static_cast<double>(samples));
        image.coverage[index] = static_cast<float>(static_cast<double>(sum.hits) / static_cast<double>(samples));
        image.edge[index] = sum.mixed ? 1 : 0;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Content hash and cache files

// FNV-1a, 64 bits: simple, stable across runs and builds, and fast enough for megabytes of
// vertices. Values are hashed as their in-memory bytes (little-endian on every target aasim
// builds for); sizes go in before arrays so [a][bc] and [ab][c] differ.
class Fnv1a {
 public:
  void Bytes(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ULL;
    }
  }
  template <typename T>
  void Value(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    Bytes(&value, sizeof(T));
  }
  template <typename T>
  void Array(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    Value(std::uint64_t{values.size()});
    Bytes(values.data(), values.size() * sizeof(T));
  }
  std::uint64_t Digest() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

constexpr std::array<char, 8> kFileMagic{'a', 'a', 's', 'i', 'm', 'G', 'T', '\n'};

// Fixed-width little-endian header in front of the payload (docs/scenes.md, "Ground truth").
struct FileHeader {
  std::array<char, 8> magic = kFileMagic;
  std::uint32_t version = kFormatVersion;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t samplesPerPixel = 0;
  std::uint64_t key = 0;
  std::uint64_t payloadBytes = 0;
  std::uint64_t payloadHash = 0;
};
static_assert(sizeof(FileHeader) == 48 && std::is_trivially_copyable_v<FileHeader>);

std::uint64_t PayloadBytes(std::size_t pixels) {
  return std::uint64_t{pixels} * (sizeof(glm::vec3) + sizeof(float) + sizeof(std::uint8_t));
}

std::uint64_t PayloadHash(const GroundTruthImage& image) {
  Fnv1a hash;
  hash.Bytes(image.colour.data(), image.colour.size() * sizeof(glm::vec3));
  hash.Bytes(image.coverage.data(), image.coverage.size() * sizeof(float));
  hash.Bytes(image.edge.data(), image.edge.size());
  return hash.Digest();
}

// The cached image, nullopt when there is no file (problem stays empty) or it fails a check
// (problem says which).
std::optional<GroundTruthImage> ReadCacheFile(const std::filesystem::path& path, std::uint64_t key,
                                              const GroundTruthSettings& settings, std::string& problem) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return std::nullopt;
  const std::size_t pixels = static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height);
  const std::uint64_t payloadBytes = PayloadBytes(pixels);
  if (size != sizeof(FileHeader) + payloadBytes) {
    problem = "size " + std::to_string(size) + " bytes, expected " + std::to_string(sizeof(FileHeader) + payloadBytes);
    return std::nullopt;
  }
  std::ifstream file(path, std::ios::binary);
  FileHeader header;
  file.read(reinterpret_cast<char*>(&header), sizeof header);
  if (!file) {
    problem = "cannot read the header";
    return std::nullopt;
  }
  if (header.magic != kFileMagic || header.version != kFormatVersion || header.key != key ||
      header.width != static_cast<std::uint32_t>(settings.width) ||
      header.height != static_cast<std::uint32_t>(settings.height) ||
      header.samplesPerPixel != static_cast<std::uint32_t>(settings.samplesPerPixel) ||
      header.payloadBytes != payloadBytes) {
    problem = "header does not match (another version, key or image size)";
    return std::nullopt;
  }
  GroundTruthImage image;
  image.width = settings.width;
  image.height = settings.height;
  image.samplesPerPixel = settings.samplesPerPixel;
  image.colour.resize(pixels);
  image.coverage.resize(pixels);
  image.edge.resize(pixels);
  file.read(reinterpret_cast<char*>(image.colour.data()), static_cast<std::streamsize>(pixels * sizeof(glm::vec3)));
  file.read(reinterpret_cast<char*>(image.coverage.data()), static_cast<std::streamsize>(pixels * sizeof(float)));
  file.read(reinterpret_cast<char*>(image.edge.data()), static_cast<std::streamsize>(pixels));
  if (!file) {
    problem = "cannot read the payload";
    return std::nullopt;
  }
  if (PayloadHash(image) != header.payloadHash) {
    problem = "payload hash mismatch";
    return std::nullopt;
  }
  return image;
}

// Temporary file in the same directory (so the rename cannot cross file systems), named by
// process and a counter so concurrent writers never share one; the rename replaces the old file
// in one step.
void WriteCacheFile(const std::filesystem::path& path, std::uint64_t key, const GroundTruthImage& image) {
  static std::atomic<std::uint64_t> counter{0};
  std::filesystem::create_directories(path.parent_path());
  const std::filesystem::path temporary =
      path.string() + ".tmp." + std::to_string(getpid()) + "." + std::to_string(counter++);
  FileHeader header;
  header.width = static_cast<std::uint32_t>(image.width);
  header.height = static_cast<std::uint32_t>(image.height);
  header.samplesPerPixel = static_cast<std::uint32_t>(image.samplesPerPixel);
  header.key = key;
  header.payloadBytes = PayloadBytes(image.colour.size());
  header.payloadHash = PayloadHash(image);
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(&header), sizeof header);
    file.write(reinterpret_cast<const char*>(image.colour.data()),
               static_cast<std::streamsize>(image.colour.size() * sizeof(glm::vec3)));
    file.write(reinterpret_cast<const char*>(image.coverage.data()),
               static_cast<std::streamsize>(image.coverage.size() * sizeof(float)));
    file.write(reinterpret_cast<const char*>(image.edge.data()), static_cast<std::streamsize>(image.edge.size()));
    file.close();
    if (!file) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error("cannot write " + temporary.string());
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot rename into " + path.string() + ": " + error.message());
  }
}

}  // namespace

GroundTruthImage RenderGroundTruth(const Scene& scene, const Camera& camera, const GroundTruthSettings& settings,
                                   const ProgressCallback& progress) {
  ValidateSettings(camera, settings);
  ValidateScene(scene);

  // Embree sets flush-to-zero and denormals-are-zero on this thread around its BVH build and runs
  // the build through oneTBB. When that is the thread's first oneTBB work, oneTBB sets up the
  // thread's arena inside that window and applies its float settings to every later parallel loop
  // of the thread: the machine and the passes would flush denormals after a rendered ground truth
  // and not after a cached one. An empty loop first sets the arena up under the caller's settings.
  tbb::parallel_for(0, 1, [](int) {});
  EmbreeErrors errors;
  const DeviceHandle device(rtcNewDevice(nullptr));
  if (!device) throw std::runtime_error(ErrorPrefix() + "cannot create an Embree device");
  rtcSetDeviceErrorFunction(device.get(), &EmbreeErrors::Record, &errors);
  const SceneHandle embree = BuildEmbreeScene(device.get(), scene);
  errors.ThrowIfAny();

  const std::vector<ShadedMesh> meshes = PrepareMeshes(scene);
  const RenderContext context{scene, settings, embree.get(), meshes,
                              RayGenerator(camera, settings.width, settings.height),
                              StrataPerSide(settings.samplesPerPixel)};

  GroundTruthImage image;
  image.width = settings.width;
  image.height = settings.height;
  image.samplesPerPixel = settings.samplesPerPixel;
  const std::size_t pixels = static_cast<std::size_t>(settings.width) * static_cast<std::size_t>(settings.height);
  image.colour.resize(pixels);
  image.coverage.resize(pixels);
  image.edge.resize(pixels);

  const int tilesX = (settings.width + kTileSize - 1) / kTileSize;
  const int tilesY = (settings.height + kTileSize - 1) / kTileSize;
  std::mutex progressMutex;
  std::size_t pixelsDone = 0;
  tbb::parallel_for(tbb::blocked_range<int>(0, tilesX * tilesY), [&](const tbb::blocked_range<int>& range) {
    for (int tile = range.begin(); tile != range.end(); ++tile) {
      const int tileX = tile % tilesX, tileY = tile / tilesX;
      RenderTile(context, tileX, tileY, image);
      if (progress) {
        const std::size_t tilePixels = static_cast<std::size_t>(std::min(kTileSize, settings.width - tileX * kTileSize)) *
                                       static_cast<std::size_t>(std::min(kTileSize, settings.height - tileY * kTileSize));
        const std::lock_guard lock(progressMutex);
        pixelsDone += tilePixels;
        progress(static_cast<double>(pixelsDone) / static_cast<double>(pixels));
      }
    }
  });
  errors.ThrowIfAny();
  return image;
}

std::uint64_t GroundTruthKey(const Scene& scene, const Camera& camera, const GroundTruthSettings& settings) {
  Fnv1a hash;
  hash.Value(kFileMagic);
  hash.Value(kFormatVersion);
  hash.Value(settings.width);
  hash.Value(settings.height);
  hash.Value(settings.samplesPerPixel);
  hash.Value(settings.clearColour);
  hash.Value(camera.eye);
  hash.Value(camera.target);
  hash.Value(camera.up);
  hash.Value(camera.verticalFovRadians);
  hash.Value(camera.zNear);
  hash.Value(camera.zFar);
  hash.Value(scene.lighting.towardsLight);
  hash.Value(scene.lighting.ambient);
  hash.Value(std::uint64_t{scene.meshes.size()});
  for (const Mesh& mesh : scene.meshes) {
    hash.Array(mesh.positions);
    hash.Array(mesh.normals);
    hash.Array(mesh.texcoords);
    hash.Array(mesh.indices);
    hash.Value(mesh.material);
  }
  hash.Value(std::uint64_t{scene.materials.size()});
  for (const Material& material : scene.materials) {
    hash.Value(material.baseColourFactor);
    hash.Value(material.baseColourTexture);
  }
  hash.Value(std::uint64_t{scene.textures.size()});
  for (const Texture& texture : scene.textures) {
    hash.Value(texture.width);
    hash.Value(texture.height);
    hash.Array(texture.texels);
  }
  return hash.Digest();
}

GroundTruthCache::GroundTruthCache(std::filesystem::path directory) : directory_(std::move(directory)) {}

std::filesystem::path GroundTruthCache::DefaultDirectory() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  // The XDG base-directory spec says to ignore relative paths.
  if (xdg != nullptr && std::filesystem::path(xdg).is_absolute()) {
    return std::filesystem::path(xdg) / "aasim" / "ground-truth";
  }
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0') return std::filesystem::path(home) / ".cache" / "aasim" / "ground-truth";
  throw std::runtime_error("ground-truth cache: neither XDG_CACHE_HOME (absolute) nor HOME is set");
}

std::filesystem::path GroundTruthCache::FileFor(std::uint64_t key) const {
  std::array<char, 17> hex{};
  std::snprintf(hex.data(), hex.size(), "%016llx", static_cast<unsigned long long>(key));
  return directory_ / (std::string(hex.data()) + ".gt");
}

CachedGroundTruth GroundTruthCache::LoadOrRender(const Scene& scene, const Camera& camera,
                                                 const GroundTruthSettings& settings,
                                                 const ProgressCallback& progress) const {
  ValidateSettings(camera, settings);
  const std::uint64_t key = GroundTruthKey(scene, camera, settings);
  CachedGroundTruth result;
  result.file = FileFor(key);
  std::string problem;
  if (std::optional<GroundTruthImage> cached = ReadCacheFile(result.file, key, settings, problem)) {
    result.image = std::move(*cached);
    result.cacheHit = true;
    return result;
  }
  if (!problem.empty()) {
    std::fprintf(stderr, "aasim: warning: ground-truth cache %s is corrupt (%s); rendering it again\n",
                 result.file.c_str(), problem.c_str());
  }
  result.image = RenderGroundTruth(scene, camera, settings, progress);
  try {
    WriteCacheFile(result.file, key, result.image);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aasim: warning: ground truth not cached: %s\n", e.what());
  }
  return result;
}

ProgressCallback StderrProgressBar(std::string label, bool force) {
  if (!force && isatty(STDERR_FILENO) == 0) return {};
  auto lastPercent = std::make_shared<int>(-1);
  return [label = std::move(label), lastPercent](double fraction) {
    const int percent = std::clamp(static_cast<int>(fraction * 100.0), 0, 100);
    if (percent == *lastPercent) return;
    *lastPercent = percent;
    constexpr int kBarWidth = 40;
    const int filled = percent * kBarWidth / 100;
    std::fprintf(stderr, "\r%s [%s%s] %3d%%", label.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kBarWidth - filled), ' ').c_str(), percent);
    if (percent == 100) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

}  // namespace scenes
