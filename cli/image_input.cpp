// Reading the user's PNG and OpenEXR images (see image_input.h).

#include "cli/image_input.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <memory>
#include <new>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <stb_image.h>

#include "scenes/scene.h"
#include "scenes/texture.h"
#include "sim/formats.h"

namespace cli {
namespace {

namespace fs = std::filesystem;

enum class FileKind { Png, Exr, Other };

// OpenEXR's magic number (openexr.com, "OpenEXR File Layout": 20000630 little-endian).
constexpr std::array<std::uint8_t, 4> kExrMagic = {0x76, 0x2f, 0x31, 0x01};

std::string Named(const fs::path& path, const std::string& problem) { return path.string() + ": " + problem; }

// A PNG of kMaxImageTexels RGBA texels stored without compression is 256 MiB; anything much
// larger is not an image aasim would decode.
constexpr std::uintmax_t kMaxPngBytes = std::uintmax_t{1} << 30;
// Enough for either signature.
constexpr std::size_t kSignatureBytes = 8;

// The first `limit` bytes of the file, all of a PNG: PNGs are decoded from memory, OpenEXR files
// by the library from the path. A FIFO or a device is refused rather than read, so the command
// cannot block on it.
std::vector<std::uint8_t> ReadBytes(const fs::path& path, std::uintmax_t limit) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (status.type() == fs::file_type::not_found) throw InputImageError(Named(path, "no such file"));
  if (error) throw InputImageError(Named(path, "cannot examine: " + error.message()));
  if (!fs::is_regular_file(status)) throw InputImageError(Named(path, "not a regular file"));
  const std::uintmax_t size = fs::file_size(path, error);
  std::ifstream file(path, std::ios::binary);
  if (error || !file) throw InputImageError(Named(path, "cannot open"));
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(std::min(size, limit)));
  if (!file.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()))) {
    throw InputImageError(Named(path, "cannot read"));
  }
  return bytes;
}

FileKind KindOf(std::span<const std::uint8_t> bytes) {
  if (scenes::SniffImageFormat(bytes) == scenes::ImageFormat::Png) return FileKind::Png;
  if (bytes.size() >= kExrMagic.size() && std::equal(kExrMagic.begin(), kExrMagic.end(), bytes.begin())) {
    return FileKind::Exr;
  }
  return FileKind::Other;
}

std::string Dimensions(long long width, long long height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// The limits scenes::ReadImageSize applies to PNG and JPEG headers, for OpenEXR data windows.
void CheckSizeLimits(const fs::path& path, long long width, long long height) {
  const std::string size = "image size " + Dimensions(width, height);
  if (width <= 0 || height <= 0) throw InputImageError(Named(path, size + " is empty"));
  if (width > scenes::kMaxImageSide || height > scenes::kMaxImageSide) {
    throw InputImageError(Named(path, size + " exceeds " + std::to_string(scenes::kMaxImageSide) +
                                          " texels on a side, the most aasim decodes"));
  }
  const auto texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (texels > scenes::kMaxImageTexels) {
    throw InputImageError(Named(path, size + " is " + std::to_string(texels) + " texels, more than the " +
                                          std::to_string(scenes::kMaxImageTexels) + " aasim decodes"));
  }
}

std::vector<std::string> ChannelNames(const Imf::Header& header) {
  std::vector<std::string> names;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) names.emplace_back(it.name());
  return names;
}

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text.empty() ? "none" : text;
}

struct ExrPlanes {
  int width = 0, height = 0;
  std::vector<std::string> names;          // as selected
  std::vector<std::vector<float>> planes;  // one per name, row-major, top row first
};

// Picks the channels to read from the file's channel names; throws InputImageError to refuse.
using ChannelSelection = std::function<std::vector<std::string>(const std::vector<std::string>& available)>;

// OpenEXR's own header checks refuse a data window or tile wider or taller than aasim decodes
// before the library allocates for it (its line offset table alone could take gigabytes). The
// limits are process-wide and default to none (0), so they hold only while the header is read:
// a writer elsewhere in the process keeps its own.
std::unique_ptr<Imf::InputFile> OpenExr(const fs::path& path) {
  struct Limits {
    Limits() { Set(scenes::kMaxImageSide); }
    ~Limits() { Set(0); }
    static void Set(int side) {
      Imf::Header::setMaxImageSize(side, side);
      Imf::Header::setMaxTileSize(side, side);
    }
  } limits;
  return std::make_unique<Imf::InputFile>(path.c_str());
}

ExrPlanes ReadExrPlanesOrThrow(const fs::path& path, const ChannelSelection& select, const ImageSizeCheck& checkSize) {
  const std::unique_ptr<Imf::InputFile> opened = OpenExr(path);
  Imf::InputFile& file = *opened;
  const Imath::Box2i window = file.header().dataWindow();
  const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
  const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
  CheckSizeLimits(path, width, height);
  if (!file.isComplete()) throw InputImageError(Named(path, "truncated: the OpenEXR file lacks some of its pixels"));
  ExrPlanes exr{static_cast<int>(width), static_cast<int>(height), select(ChannelNames(file.header())), {}};
  checkSize(exr.width, exr.height);
  const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  Imf::FrameBuffer frameBuffer;
  for (const std::string& name : exr.names) {
    std::vector<float>& plane = exr.planes.emplace_back(texels);
    frameBuffer.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data(), window));
  }
  file.setFrameBuffer(frameBuffer);
  file.readPixels(window.min.y, window.max.y);
  for (std::size_t c = 0; c < exr.planes.size(); ++c) {
    const std::vector<float>& plane = exr.planes[c];
    const auto bad = std::find_if(plane.begin(), plane.end(), [](float v) { return !std::isfinite(v); });
    if (bad == plane.end()) continue;
    const auto at = static_cast<std::size_t>(bad - plane.begin());
    throw InputImageError(Named(path, "channel " + exr.names[c] + " of pixel (" +
                                          std::to_string(at % static_cast<std::size_t>(width)) + ", " +
                                          std::to_string(at / static_cast<std::size_t>(width)) + ") is " +
                                          std::to_string(*bad) + "; aasim reads finite values only"));
  }
  return exr;
}

// OpenEXR's exceptions (a malformed or truncated file) as InputImageError naming the file.
ExrPlanes ReadExrPlanes(const fs::path& path, const ChannelSelection& select, const ImageSizeCheck& checkSize) {
  try {
    return ReadExrPlanesOrThrow(path, select, checkSize);
  } catch (const InputImageError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& error) {
    throw InputImageError(Named(path, std::string("cannot read OpenEXR: ") + error.what()));
  }
}

bool Has(const std::vector<std::string>& names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

InputImage ReadColourExr(const fs::path& path, const ImageSizeCheck& checkSize) {
  bool alpha = false;
  const ExrPlanes exr = ReadExrPlanes(
      path,
      [&](const std::vector<std::string>& available) {
        if (!Has(available, "R") || !Has(available, "G") || !Has(available, "B")) {
          throw InputImageError(Named(path, "OpenEXR channels " + Join(available) +
                                                "; a colour image needs R, G and B (A optional)"));
        }
        alpha = Has(available, "A");
        std::vector<std::string> names{"R", "G", "B"};
        if (alpha) names.emplace_back("A");
        return names;
      },
      checkSize);
  InputImage image{"exr", alpha, {"colour", exr.width, exr.height, 4}};
  std::span<glm::vec4> texels = image.colour.Texels();
  for (std::size_t t = 0; t < texels.size(); ++t) {
    texels[t] = {exr.planes[0][t], exr.planes[1][t], exr.planes[2][t], alpha ? exr.planes[3][t] : 1.0f};
  }
  return image;
}

std::vector<std::uint8_t> ReadPng(const fs::path& path) {
  std::vector<std::uint8_t> bytes = ReadBytes(path, kMaxPngBytes + 1);
  if (bytes.size() > kMaxPngBytes) {
    throw InputImageError(
        Named(path, "more than the " + std::to_string(kMaxPngBytes) + " bytes aasim reads for a PNG"));
  }
  return bytes;
}

// stb_image refuses a PNG whose IHDR declares no texels as an "unknown image type"; the header
// itself says what is wrong (PNG spec §11.2.2: IHDR comes first, width and height at bytes 16 and
// 20 of the file, big-endian).
void CheckPngNotEmpty(const fs::path& path, std::span<const std::uint8_t> bytes) {
  if (bytes.size() < 24 || !std::equal(bytes.begin() + 12, bytes.begin() + 16, "IHDR")) return;
  auto word = [&](std::size_t at) {
    return std::uint32_t{bytes[at]} << 24 | std::uint32_t{bytes[at + 1]} << 16 | std::uint32_t{bytes[at + 2]} << 8 |
           std::uint32_t{bytes[at + 3]};
  };
  if (word(16) == 0 || word(20) == 0) {
    throw InputImageError(Named(path, "image size " + Dimensions(word(16), word(20)) + " is empty"));
  }
}

// stb_image's view of the header; ReadImageSize has already accepted it.
struct PngLayout {
  int channels = 0;
  bool wide = false;
};

PngLayout LayoutOf(std::span<const std::uint8_t> bytes) {
  const int length = static_cast<int>(bytes.size());
  int width = 0, height = 0;
  PngLayout layout;
  stbi_info_from_memory(bytes.data(), length, &width, &height, &layout.channels);
  layout.wide = stbi_is_16_bit_from_memory(bytes.data(), length) != 0;
  return layout;
}

InputImage ReadColourPng(const fs::path& path, std::span<const std::uint8_t> bytes, const ImageSizeCheck& checkSize) {
  CheckPngNotEmpty(path, bytes);
  try {
    const scenes::ImageSize size = scenes::ReadImageSize(bytes, path.string());
    const PngLayout layout = LayoutOf(bytes);
    if (layout.wide) {
      throw InputImageError(Named(path, "16 bits per channel; aasim reads 8-bit PNG (sRGB) or OpenEXR (linear)"));
    }
    checkSize(size.width, size.height);
    // Linear decoding gives code / 255, from which the code is recovered exactly.
    const scenes::Texture decoded = scenes::DecodeImage(bytes, path.string(), scenes::ColourEncoding::Linear);
    // A grey or RGB PNG with a transparent colour (tRNS) decodes with alpha too.
    const bool alpha = layout.channels == 2 || layout.channels == 4 ||
                       std::any_of(decoded.texels.begin(), decoded.texels.end(),
                                   [](const glm::vec4& texel) { return texel.a != 1.0f; });
    InputImage image{"png", alpha, {"colour", size.width, size.height, 4}};
    std::span<glm::vec4> texels = image.colour.Texels();
    // Colour through an sRGB view, alpha as a UNORM8 channel reads (sim/formats.h).
    auto code8 = [](float unorm) { return static_cast<std::uint8_t>(std::lround(unorm * 255.0f)); };
    for (std::size_t t = 0; t < texels.size(); ++t) {
      const glm::vec4& code = decoded.texels[t];
      texels[t] = {sim::Srgb8ToFloat(code8(code.r)), sim::Srgb8ToFloat(code8(code.g)), sim::Srgb8ToFloat(code8(code.b)),
                   sim::Unorm8ToFloat(code8(code.a))};
    }
    return image;
  } catch (const scenes::SceneError& error) {
    throw InputImageError(error.what());
  }
}

}  // namespace

InputImage ReadInputImage(const fs::path& path, const ImageSizeCheck& checkSize) {
  switch (KindOf(ReadBytes(path, kSignatureBytes))) {
    case FileKind::Png: return ReadColourPng(path, ReadPng(path), checkSize);
    case FileKind::Exr: return ReadColourExr(path, checkSize);
    case FileKind::Other: break;
  }
  throw InputImageError(Named(path, "not a PNG or OpenEXR file (no PNG or OpenEXR signature)"));
}

namespace {
// The image's size or an error naming both files.
ImageSizeCheck SameSize(const fs::path& path, std::string_view what, int width, int height, const std::string& image) {
  return [=, what = std::string(what)](int fileWidth, int fileHeight) {
    if (fileWidth == width && fileHeight == height) return;
    throw InputImageError(Named(path, what + " is " + Dimensions(fileWidth, fileHeight) + ", the image " + image +
                                          " is " + Dimensions(width, height)));
  };
}
}  // namespace

VelocityImage ReadVelocityExr(const fs::path& path, int width, int height, const std::string& image) {
  if (KindOf(ReadBytes(path, kSignatureBytes)) != FileKind::Exr) {
    throw InputImageError(Named(path, "not an OpenEXR file (no OpenEXR signature); velocity is read from OpenEXR only"));
  }
  std::string channels;
  const ExrPlanes exr = ReadExrPlanes(
      path,
      [&](const std::vector<std::string>& available) {
        for (const std::string_view pair : {"RG", "XY"}) {
          const std::string x(1, pair[0]), y(1, pair[1]);
          if (Has(available, x) && Has(available, y)) {
            channels = std::string(pair);
            return std::vector<std::string>{x, y};
          }
        }
        throw InputImageError(Named(path, "OpenEXR channels " + Join(available) +
                                              "; velocity is read from channels R and G, or X and Y"));
      },
      SameSize(path, "velocity", width, height, image));
  VelocityImage velocity{channels, {"velocity", width, height, 8}};
  for (std::size_t i = 0; i < exr.planes[0].size(); ++i) {
    velocity.velocity.Texels()[i] = glm::vec2(exr.planes[0][i], exr.planes[1][i]);
  }
  return velocity;
}

DepthImage ReadDepthExr(const fs::path& path, int width, int height, const std::string& image) {
  if (KindOf(ReadBytes(path, kSignatureBytes)) != FileKind::Exr) {
    throw InputImageError(Named(path, "not an OpenEXR file (no OpenEXR signature); depth is read from OpenEXR only"));
  }
  std::string channel;
  const ExrPlanes exr = ReadExrPlanes(
      path,
      [&](const std::vector<std::string>& available) {
        const auto found = std::find_if(std::begin(kDepthChannels), std::end(kDepthChannels),
                                        [&](std::string_view name) { return Has(available, name); });
        if (found == std::end(kDepthChannels)) {
          throw InputImageError(Named(path, "OpenEXR channels " + Join(available) +
                                                "; depth is read from a channel named Z, Y or R"));
        }
        channel = std::string(*found);
        return std::vector<std::string>{channel};
      },
      [&](int depthWidth, int depthHeight) {
        if (depthWidth == width && depthHeight == height) return;
        throw InputImageError(Named(path, "depth is " + Dimensions(depthWidth, depthHeight) + ", the image " + image +
                                              " is " + Dimensions(width, height)));
      });
  DepthImage depth{channel, {"depth", width, height, 4}};
  std::copy(exr.planes[0].begin(), exr.planes[0].end(), depth.depth.Texels().begin());
  return depth;
}

}  // namespace cli
