// The frame pipeline (see frame.h).

#include "sim/frame.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "sim/eqaa_resolve.h"

namespace sim {

namespace {

void CheckPatternFits(const raster::SamplePattern& pattern, const fmask::EqaaConfig& eqaa) {
  if (pattern.Count() != eqaa.coverageSamples) {
    throw std::invalid_argument("sample pattern '" + pattern.Name() + "' has " + std::to_string(pattern.Count()) +
                                " samples, the EQAA mode " + fmask::EqaaName(eqaa) + " needs " +
                                std::to_string(eqaa.coverageSamples));
  }
}

raster::DepthSurfaceConfig DepthConfig(const FrameSettings& settings) {
  fmask::ValidateEqaaConfig(settings.eqaa);
  CheckPatternFits(settings.pattern, settings.eqaa);
  if (settings.sampleRateShading && settings.eqaa.coverageSamples != 1) {
    throw std::invalid_argument("sample-rate shading needs a one-sample surface, not " + fmask::EqaaName(settings.eqaa));
  }
  raster::DepthSurfaceConfig config;
  config.width = settings.width;
  config.height = settings.height;
  config.coverageSamples = settings.eqaa.coverageSamples;
  config.depthSamples = settings.eqaa.depthSamples;
  config.maxZPlanes = settings.maxZPlanes;
  return config;
}

glm::vec2 ClipToScreen(const glm::vec4& clip, int width, int height) {
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x + 1.0f) * 0.5f * static_cast<float>(width), (1.0f - ndc.y) * 0.5f * static_cast<float>(height)};
}

template <typename T>
T Interpolate(std::span<const T> values, std::span<const std::uint32_t> corners, const std::array<float, 3>& b) {
  return values[corners[0]] * b[0] + values[corners[1]] * b[1] + values[corners[2]] * b[2];
}

// The nearest depth of a triangle (DrawOrderPermutation's key). A NaN coordinate gives 0 (w
// fails `> 0`, std::max(0, NaN) is 0), so keys are never NaN and the sort's comparison is a
// strict weak order whatever the input holds.
float NearestDepth(std::span<const glm::vec4> positions, std::span<const std::uint32_t> corners) {
  float nearest = 1.0f;
  for (const std::uint32_t corner : corners) {
    const glm::vec4& p = positions[corner];
    const float depth = p.w > 0.0f ? std::max(0.0f, p.z / p.w) : 0.0f;
    if (depth < nearest) nearest = depth;
  }
  return nearest;
}

}  // namespace

std::vector<std::uint32_t> DrawOrderPermutation(const FrameGeometry& geometry, DrawOrder order) {
  const std::size_t triangles = geometry.indices.size() / 3;
  std::vector<std::uint32_t> permutation(triangles);
  std::iota(permutation.begin(), permutation.end(), 0u);
  if (order == DrawOrder::Submission) return permutation;
  std::vector<float> key(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    key[t] = NearestDepth(geometry.clipPositions, geometry.indices.subspan(3 * t, 3));
  }
  if (order == DrawOrder::ObjectsFrontToBack) {
    std::vector<float> objectKey(geometry.baseColours.size(), 1.0f);
    for (std::size_t t = 0; t < triangles; ++t) {
      float& nearest = objectKey[geometry.objectIds[t]];
      nearest = std::min(nearest, key[t]);
    }
    for (std::size_t t = 0; t < triangles; ++t) key[t] = objectKey[geometry.objectIds[t]];
  }
  std::ranges::stable_sort(permutation, {}, [&](std::uint32_t t) { return key[t]; });
  return permutation;
}

FramePipeline::FramePipeline(Machine& machine, FrameSettings settings)
    : machine_(machine), settings_(std::move(settings)), depth_(DepthConfig(settings_), settings_.pattern),
      eqaa_(settings_.width, settings_.height, settings_.eqaa, settings_.policy, fmask::InitialState::Cleared,
            settings_.clearColour),
      colour_("colour", settings_.width, settings_.height, 4),
      colourSrgb8_("colour-srgb8", settings_.width, settings_.height, Format::RGBA8Srgb),
      depthTarget_("depth", settings_.width, settings_.height, 4),
      normal_("normal", settings_.width, settings_.height, 4),  // modelled as RGB10A2
      objectId_("object-id", settings_.width, settings_.height, 4),
      velocity_("velocity", settings_.width, settings_.height, 4) {}  // modelled as RG16F

void FramePipeline::Validate(const FrameGeometry& geometry) const {
  const std::size_t vertices = geometry.clipPositions.size();
  const std::size_t triangles = geometry.indices.size() / 3;
  if (geometry.indices.size() % 3 != 0) {
    throw std::invalid_argument("frame geometry: index count " + std::to_string(geometry.indices.size()) +
                                " is not a multiple of 3");
  }
  if (!geometry.previousClipPositions.empty() && geometry.previousClipPositions.size() != vertices) {
    throw std::invalid_argument("frame geometry: " + std::to_string(geometry.previousClipPositions.size()) +
                                " previous positions for " + std::to_string(vertices) + " vertices");
  }
  if (geometry.normals.size() != vertices) {
    throw std::invalid_argument("frame geometry: " + std::to_string(geometry.normals.size()) + " normals for " +
                                std::to_string(vertices) + " vertices");
  }
  if (geometry.objectIds.size() != triangles) {
    throw std::invalid_argument("frame geometry: " + std::to_string(geometry.objectIds.size()) +
                                " object ids for " + std::to_string(triangles) + " triangles");
  }
  ValidateTextures(geometry);
  for (std::size_t t = 0; t < triangles; ++t) {
    if (geometry.objectIds[t] >= geometry.baseColours.size()) {
      throw std::invalid_argument("frame geometry: triangle " + std::to_string(t) + " names object " +
                                  std::to_string(geometry.objectIds[t]) + " of " +
                                  std::to_string(geometry.baseColours.size()));
    }
  }
}

void FramePipeline::ValidateTextures(const FrameGeometry& geometry) const {
  if (!geometry.texcoords.empty() && geometry.texcoords.size() != geometry.clipPositions.size()) {
    throw std::invalid_argument("frame geometry: " + std::to_string(geometry.texcoords.size()) + " texcoords for " +
                                std::to_string(geometry.clipPositions.size()) + " vertices");
  }
  if (!geometry.baseColourTextures.empty() && geometry.baseColourTextures.size() != geometry.baseColours.size()) {
    throw std::invalid_argument("frame geometry: " + std::to_string(geometry.baseColourTextures.size()) +
                                " texture indices for " + std::to_string(geometry.baseColours.size()) + " objects");
  }
  for (std::size_t object = 0; object < geometry.baseColourTextures.size(); ++object) {
    const int texture = geometry.baseColourTextures[object];
    if (texture < -1 || texture >= static_cast<int>(geometry.textures.size())) {
      throw std::invalid_argument("frame geometry: object " + std::to_string(object) + " names texture " +
                                  std::to_string(texture) + " of " + std::to_string(geometry.textures.size()));
    }
    if (texture >= 0 && geometry.texcoords.empty()) {
      throw std::invalid_argument("frame geometry: object " + std::to_string(object) +
                                  " is textured but the geometry has no texcoords");
    }
  }
}

void FramePipeline::ClearTargets() {
  depth_.Clear(1.0f, 0);
  eqaa_.Reset(fmask::InitialState::Cleared, settings_.clearColour);
  depthTarget_.Fill(1.0f);
  normal_.Fill(glm::vec4(0.0f));
  objectId_.Fill(kNoObject);
  velocity_.Fill(glm::vec2(0.0f));
}

FrameGeometry FramePipeline::Ordered(const FrameGeometry& geometry) {
  if (settings_.drawOrder == DrawOrder::Submission) return geometry;
  const std::vector<std::uint32_t> order = DrawOrderPermutation(geometry, settings_.drawOrder);
  orderedIndices_.resize(geometry.indices.size());
  orderedObjectIds_.resize(order.size());
  for (std::size_t t = 0; t < order.size(); ++t) {
    const std::span<const std::uint32_t> corners = geometry.indices.subspan(3 * std::size_t{order[t]}, 3);
    std::copy(corners.begin(), corners.end(), orderedIndices_.begin() + 3 * static_cast<std::ptrdiff_t>(t));
    orderedObjectIds_[t] = geometry.objectIds[order[t]];
  }
  FrameGeometry ordered = geometry;
  ordered.indices = orderedIndices_;
  ordered.objectIds = orderedObjectIds_;
  return ordered;
}

void FramePipeline::DepthPrepass(const FrameGeometry& geometry) {
  Dispatch dispatch("frame/depth-prepass", kDepthPrepassKernel);
  DrawCall call;
  call.input = {geometry.clipPositions, geometry.indices, 0};
  call.state.cull = settings_.cull;
  call.depth = &depth_;
  call.flush = settings_.flush;
  machine_.DrawDepthOnly(dispatch, call);
}

DispatchReport FramePipeline::Render(const FrameGeometry& submitted, const FrameParams& params) {
  Validate(submitted);
  const FrameGeometry geometry = Ordered(submitted);
  if (params.pattern != nullptr) {
    CheckPatternFits(*params.pattern, settings_.eqaa);
    depth_.SetPattern(*params.pattern);
    settings_.pattern = *params.pattern;
  }
  frameIndex_ = params.frameIndex;
  ClearTargets();
  if (settings_.depthPrepass) DepthPrepass(geometry);
  Dispatch dispatch("frame/material", kMaterialKernel);
  const RwTextureView<float> depthOut = dispatch.ReadWrite(depthTarget_);
  const RwTextureView<glm::vec4> normalOut = dispatch.ReadWrite(normal_);
  const RwTextureView<std::uint32_t> idOut = dispatch.ReadWrite(objectId_);
  const RwTextureView<glm::vec2> velocityOut = dispatch.ReadWrite(velocity_);
  std::vector<TextureView<glm::vec4>> textures;
  textures.reserve(geometry.textures.size());
  for (const Texture2D<glm::vec4>& texture : geometry.textures) textures.push_back(dispatch.Read(texture));
  const glm::vec3 towardsLight = glm::normalize(settings_.towardsLight);
  const int width = settings_.width, height = settings_.height;
  const float ambient = settings_.ambient;
  const bool sampleRate = settings_.sampleRateShading;

  auto material = [&](PixelLane& lane) -> fmask::Colour {
    const std::uint32_t primitive = lane.quad->primitiveId;
    const std::span<const std::uint32_t> corners = geometry.indices.subspan(3 * std::size_t{primitive}, 3);
    // Centroid interpolation keeps partially covered pixels from extrapolating the normal.
    const std::array<float, 3> b = sampleRate ? lane.SampleBarycentrics(0) : lane.CentroidBarycentrics();
    glm::vec3 normal = glm::normalize(Interpolate(geometry.normals, corners, b));
    if (!lane.quad->frontFacing) normal = -normal;
    const std::uint32_t object = geometry.objectIds[primitive];
    glm::vec3 base = geometry.baseColours[object];
    const int texture = geometry.baseColourTextures.empty() ? -1 : geometry.baseColourTextures[object];
    if (texture >= 0) {
      const glm::vec2 uv = Interpolate(geometry.texcoords, corners, b);
      base *= glm::vec3(textures[static_cast<std::size_t>(texture)].SampleBilinear(lane, uv, AddressMode::Repeat));
    }
    const float lambert = std::max(0.0f, glm::dot(normal, towardsLight));
    const glm::vec3 shaded = base * (ambient + (1.0f - ambient) * lambert);
    if ((lane.Passed() & 1u) != 0) {
      const glm::vec4 current = Interpolate(geometry.clipPositions, corners, b);
      glm::vec2 velocity(0.0f);
      if (!geometry.previousClipPositions.empty()) {
        const glm::vec4 previous = Interpolate(geometry.previousClipPositions, corners, b);
        velocity = ClipToScreen(current, width, height) - ClipToScreen(previous, width, height);
      }
      depthOut.Store(lane, lane.x, lane.y,
                     lane.triangle->depth.Evaluate(raster::SampleX(lane.x, 0), raster::SampleY(lane.y, 0)));
      normalOut.Store(lane, lane.x, lane.y, glm::vec4(normal, 1.0f));
      idOut.Store(lane, lane.x, lane.y, object);
      velocityOut.Store(lane, lane.x, lane.y, velocity);
    }
    return {shaded.r, shaded.g, shaded.b, 1.0f};
  };

  DrawCall call;
  call.input = {geometry.clipPositions, geometry.indices, 0};
  call.state.cull = settings_.cull;
  if (settings_.depthPrepass) {
    // The pre-pass stored exactly this draw's depths (same set-ups, same sample positions, the
    // same plane evaluation), so EQUAL passes where the triangle is the visible one.
    call.state.depth.func = raster::CompareFunc::Equal;
    call.state.depth.writeEnable = false;
  }
  call.depth = &depth_;
  call.colour = &eqaa_;
  call.flush = settings_.flush;
  DispatchReport report = machine_.Draw(dispatch, call, material);
  fragments_ = report.fragments.value_or(fmask::FragmentCounters{});
  Resolve();
  return report;
}

void FramePipeline::Resolve() {
  RunBoxResolve(machine_, eqaa_, colour_, "frame/resolve");
  StoreSrgb8(colour_, colourSrgb8_);
}

}  // namespace sim
