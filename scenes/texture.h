#pragma once
// Texture decoding: PNG and JPEG files, and 8- or 16-bit images with 1 to 4 channels (the
// layouts stb_image produces), become the linear RGBA floats of scenes::Texture. Colour channels
// of base colour textures are sRGB-encoded (glTF), so they pass through the IEC 61966-2-1
// decoding curve; alpha is linear.

#include <cstddef>
#include <cstdint>
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

// Limits on one decoded image, checked from the file's header before any texel is decoded: at
// most 16384 texels on a side (the largest D3D11 texture) and 2^26 texels in all (8192 x 8192,
// 1 GiB as linear RGBA floats). A 20000 x 20000 PNG of a few hundred kilobytes would otherwise
// claim 6.4 GB.
inline constexpr int kMaxImageSide = 16384;
inline constexpr std::size_t kMaxImageTexels = std::size_t{1} << 26;
// And a JPEG may declare at most 512 texels per byte of file. Huffman coding (ITU-T T.81 F.1.2,
// and G.1.2.1 for a progressive DC scan; stb_image reads no arithmetic-coded JPEG) spends at
// least one bit on every 8x8 block of the full-resolution component, its DC difference, so no
// real JPEG holds more than 64 x 8 texels per byte; a flat colour written by stb_image_write comes
// to 62 at 1024 x 1024. stb_image decodes data that ends early as if zeros followed, so without
// this bound a 615-byte file declaring 8192 x 8192 decoded for 1.8 s into 1.2 GiB.
inline constexpr std::size_t kMaxJpegTexelsPerByte = 512;

enum class ImageFormat { Png, Jpeg, Other };

// By the file's signature (PNG: 89 50 4E 47 0D 0A 1A 0A; JPEG: FF D8 FF).
ImageFormat SniffImageFormat(std::span<const std::uint8_t> encoded);

struct ImageSize {
  int width = 0;
  int height = 0;
};

// A PNG's or JPEG's dimensions from its header, without decoding. Throws SceneError naming
// `name` for another format, an unreadable header, or dimensions beyond the limits above
// (kMaxJpegTexelsPerByte against `encoded`'s size for a JPEG).
ImageSize ReadImageSize(std::span<const std::uint8_t> encoded, const std::string& name);

// Decodes a PNG or JPEG (8 or 16 bits per channel, grey, grey + alpha, RGB, RGBA or palette)
// into a Texture named `name`, after ReadImageSize's checks. Throws SceneError "NAME: problem"
// for anything else, with stb_image's reason when decoding fails. Safe on any input bytes.
Texture DecodeImage(std::span<const std::uint8_t> encoded, std::string name,
                    ColourEncoding encoding);

}  // namespace scenes
