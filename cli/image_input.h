#pragma once
// The user's own images, for `aasim post`: a colour image as a capture tool such as RenderDoc
// exports a render target, either an 8-bit PNG (sRGB-encoded, what an RGBA8 sRGB target holds)
// or an OpenEXR file (linear floats, what a float target holds), and optionally a depth buffer
// as a one-channel OpenEXR file. Files are recognised by their signature, not their name. Every
// problem is an InputImageError "FILE: problem" naming the file, thrown before any texel is
// kept; the limits are those of scene textures (scenes/texture.h: kMaxImageSide on a side,
// kMaxImageTexels in all).

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "sim/resources.h"

namespace cli {

class InputImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Called with the image's size once its header has been read and before any texel is decoded,
// so a caller's memory guard can refuse it by throwing.
using ImageSizeCheck = std::function<void(int width, int height)>;

struct InputImage {
  std::string format;  // "png" or "exr"
  bool alpha = false;  // the file has an alpha channel; without one alpha is 1
  // Linear RGBA, named and sized in the traffic counters as the rendered frame's colour target.
  sim::Texture2D<glm::vec4> colour{"colour", 1, 1, 4};
};

// PNG: 8 bits per channel, grey, grey + alpha, RGB or RGBA (palette images as stb_image expands
// them). Colour codes are decoded as an sRGB view reads them (sim::Srgb8ToFloat: the nearest
// float to the IEC 61966-2-1 curve of sim/colour.h), so sim::EncodeSrgb8 gives back every code;
// alpha as a UNORM8 channel reads (sim::Unorm8ToFloat). The hardened PNG reader of scene textures does the decoding
// (scenes::DecodeImage). OpenEXR: channels R, G, B and optionally A of the data window, any
// pixel type, every value finite.
InputImage ReadInputImage(const std::filesystem::path& path, const ImageSizeCheck& checkSize);

// The channels a depth file may hold the depth in, in order of preference.
inline constexpr std::string_view kDepthChannels[] = {"Z", "Y", "R"};

struct DepthImage {
  std::string channel;  // the one read, from kDepthChannels
  sim::Texture2D<float> depth{"depth", 1, 1, 4};
};

// The first of kDepthChannels an OpenEXR file holds, every value finite. Its data window must
// be `width` x `height`, the size of the colour image `image` (named in the error).
DepthImage ReadDepthExr(const std::filesystem::path& path, int width, int height, const std::string& image);

// A velocity buffer for `aasim post` over a sequence: an OpenEXR file of the image's size whose
// channels R and G (RenderDoc's export of an RG target) or X and Y hold each pixel's motion in
// pixels, current position minus previous, +y down (sim::FramePipeline::Velocity's convention),
// every value finite.
struct VelocityImage {
  std::string channels;  // "RG" or "XY"
  sim::Texture2D<glm::vec2> velocity{"velocity", 1, 1, 8};
};
VelocityImage ReadVelocityExr(const std::filesystem::path& path, int width, int height, const std::string& image);

}  // namespace cli
