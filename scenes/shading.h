#pragma once
// The one shading model of aasim: base colour (material factor times its texture, bilinear with
// repeat wrapping) lit by Lambert with an ambient term. The raster material kernel (sim/frame.h)
// and the Embree ground truth both evaluate exactly this, so their difference is coverage and
// sampling, never the material.

#include <array>
#include <cstddef>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "scenes/scene.h"

namespace scenes {

// Meshes without a material get kMeshPalette[mesh index % size]: linear colours far enough apart
// that neighbouring meshes, and the anti-aliased edges between them, stand out.
inline constexpr std::array<glm::vec3, 8> kMeshPalette{{
    {0.80f, 0.80f, 0.80f},  // light grey
    {0.80f, 0.25f, 0.20f},  // red
    {0.25f, 0.60f, 0.25f},  // green
    {0.20f, 0.35f, 0.80f},  // blue
    {0.85f, 0.65f, 0.20f},  // amber
    {0.55f, 0.30f, 0.70f},  // purple
    {0.20f, 0.65f, 0.70f},  // teal
    {0.75f, 0.45f, 0.55f},  // pink
}};

// Bilinear, repeat wrapping, texel centres at +0.5 (glTF default sampler, linear filtering).
glm::vec4 SampleBilinearRepeat(const Texture& texture, glm::vec2 uv);

// Material factor times the base colour texture at uv (uv ignored without a texture); the
// palette colour for a mesh without a material.
glm::vec4 BaseColour(const Scene& scene, std::size_t meshIndex, glm::vec2 uv);

// baseColour * (ambient + (1 - ambient) * max(0, N.L)); `normal` must be unit length and face
// the viewer (flip back faces before calling).
glm::vec3 ShadeLambert(const Lighting& lighting, glm::vec3 baseColour, glm::vec3 normal);

}  // namespace scenes
