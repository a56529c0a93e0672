#pragma once
// Texture decoding: 8- or 16-bit images with 1 to 4 channels (the layouts stb_image produces)
// become the linear RGBA floats of scenes::Texture. Colour channels of base colour textures are
// sRGB-encoded (glTF), so they pass through the IEC 61966-2-1 decoding curve; alpha is linear.

#include <cstddef>
#include <span>
#include <string>

#include "scenes/scene.h"

namespace scenes {

enum class ColourEncoding { Linear, Srgb };

// The IEC 61966-2-1 (sRGB) decoding curve for an encoded value in [0, 1].
float SrgbToLinear(float encoded);

// `bytes` holds width * height texels, rows top first, each `channels` values of
// `bitsPerChannel` bits (16-bit values in host byte order, as stb_image returns them).
// One channel is grey, two are grey and alpha, three RGB, four RGBA; a missing alpha is 1.
// Throws SceneError naming `name` for unsupported layouts or a byte count that does not match.
Texture DecodeTexels(std::string name, int width, int height, int channels, int bitsPerChannel,
                     std::span<const unsigned char> bytes, ColourEncoding encoding);

}  // namespace scenes
