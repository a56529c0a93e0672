#pragma once
// Memory the kernels read and write: 2D textures, buffers and append buffers with their atomic
// counter. Each resource knows its modelled size in bytes (the format the hardware would store,
// not the float the host keeps) and records which 64-byte lines a dispatch touched, so traffic is
// reported both as lane requests and as distinct lines (sim/counters.h ResourceTraffic).
// Host access (At, Fill) is not counted: only views (sim/views.h) count.

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/limits.h"
#include "sim/check.h"
#include "sim/formats.h"
#include "sim/wave.h"

namespace sim {

class Resource {
 public:
  Resource(std::string name, std::size_t modelledBytes);

  const std::string& Name() const { return name_; }
  std::size_t ModelledBytes() const { return modelledBytes_; }

  // Line tracking for one dispatch. Touch* may be called from several host threads: bits are
  // set with atomic OR, which commutes, so the result does not depend on the thread count.
  void BeginDispatch();
  [[gnu::always_inline]] void TouchRead(std::size_t byteOffset, std::size_t bytes) const {
    Touch(readLines_, byteOffset, bytes);
  }
  [[gnu::always_inline]] void TouchWrite(std::size_t byteOffset, std::size_t bytes) const {
    Touch(writtenLines_, byteOffset, bytes);
  }
  std::uint64_t LinesRead() const { return CountBits(readLines_); }
  // The read-line bits, for views that mark lines without going through the resource
  // (TouchBytes); the vector never reallocates after construction.
  std::uint64_t* ReadLines() const { return readLines_.data(); }
  // Marks the lines of bytes [byteOffset, byteOffset + bytes), bytes <= kCacheLineBytes, in
  // `lines` (at most two lines).
  [[gnu::always_inline]] static void TouchBytes(std::uint64_t* lines, std::size_t byteOffset, std::size_t bytes) {
    const std::size_t first = byteOffset / kCacheLineBytes;
    const std::size_t last = (byteOffset + bytes - 1) / kCacheLineBytes;
    MarkLine(lines, first);
    if (last != first) MarkLine(lines, last);
  }
  std::uint64_t LinesWritten() const { return CountBits(writtenLines_); }

 private:
  static void Touch(std::vector<std::uint64_t>& lines, std::size_t byteOffset, std::size_t bytes);
  [[gnu::always_inline]] static void MarkLine(std::uint64_t* lines, std::size_t line) {
    std::atomic_ref<std::uint64_t> word(lines[line / 64]);
    const std::uint64_t bit = std::uint64_t{1} << (line % 64);
    // Most touches hit a line already seen: a relaxed load avoids the locked OR.
    if ((word.load(std::memory_order_relaxed) & bit) == 0) word.fetch_or(bit, std::memory_order_relaxed);
  }
  static std::uint64_t CountBits(const std::vector<std::uint64_t>& lines);

  std::string name_;
  std::size_t modelledBytes_;
  // One bit per kCacheLineBytes line; mutable because reading a resource through a view still
  // records the lines it touched.
  mutable std::vector<std::uint64_t> readLines_;
  mutable std::vector<std::uint64_t> writtenLines_;
};

[[gnu::always_inline]] inline void Resource::Touch(std::vector<std::uint64_t>& lines, std::size_t byteOffset,
                                                   std::size_t bytes) {
  const std::size_t first = byteOffset / kCacheLineBytes;
  const std::size_t last = (byteOffset + bytes - 1) / kCacheLineBytes;
  for (std::size_t line = first; line <= last; ++line) MarkLine(lines.data(), line);
}

// Row-major texels. Without a Format the host keeps T unchanged and texelBytes is only the
// modelled size (e.g. 4 for RGBA8 even though the host keeps float RGBA). With a Format
// (sim/formats.h) the size comes from it and stores through views, Set, Fill and the fill value
// are quantised. A texture of an 8-bit format (R8, RG8, RGBA8 UNORM or sRGB) keeps its codes, one
// byte per channel of the format, as the hardware does: Codes(), Get and Set; every other texture
// keeps T: Texels(), At (the raw host value) and Get/Set.
template <typename T>
class Texture2D : public Resource {
 public:
  Texture2D(std::string name, int width, int height, int texelBytes = sizeof(T), T fill = T{})
      : Texture2D(std::move(name), width, height, texelBytes, std::nullopt) {
    texels_.assign(TexelCount(), fill);
  }
  Texture2D(std::string name, int width, int height, Format format, T fill = T{})
    requires FormattableTexel<T>
      : Texture2D(CheckedFormat(std::move(name), format), width, height, BytesPerTexel(format), format) {
    if (codeChannels_ == 0) texels_.resize(TexelCount());
    Fill(fill);
  }

  int Width() const { return width_; }
  int Height() const { return height_; }
  int TexelBytes() const { return texelBytes_; }
  std::optional<Format> TexelFormat() const { return format_; }
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }

  // Bytes per texel of an 8-bit texture's codes (its format's channels), 0 for a texture that
  // keeps T.
  int CodeChannels() const { return codeChannels_; }
  bool KeepsCodes() const { return codeChannels_ != 0; }
  std::span<std::uint8_t> Codes() {
    AASIM_CHECK(KeepsCodes());
    return codes_;
  }
  std::span<const std::uint8_t> Codes() const {
    AASIM_CHECK(KeepsCodes());
    return codes_;
  }
  // Texture that keeps T only.
  T& At(int x, int y) {
    AASIM_CHECK(!KeepsCodes());
    return texels_[Index(x, y)];
  }
  const T& At(int x, int y) const {
    AASIM_CHECK(!KeepsCodes());
    return texels_[Index(x, y)];
  }
  std::span<T> Texels() {
    AASIM_CHECK(!KeepsCodes());
    return texels_;
  }
  std::span<const T> Texels() const {
    AASIM_CHECK(!KeepsCodes());
    return texels_;
  }
  // Any texture: what At holds, or an 8-bit texture's codes as its UNORM view reads them
  // (code / 255, the format's missing channels 0 and alpha 1), and a quantised host store.
  T Get(int x, int y) const {
    if constexpr (FloatTexel<T>) {
      if (KeepsCodes()) return DecodeCodes<T>(codes_.data() + Index(x, y) * CodeStride(), codeChannels_, false);
    }
    return texels_[Index(x, y)];
  }
  void Set(int x, int y, const T& value) {
    if constexpr (FloatTexel<T>) {
      if (KeepsCodes()) {
        EncodeCodes(*format_, value, codes_.data() + Index(x, y) * CodeStride(), codeChannels_);
        return;
      }
    }
    texels_[Index(x, y)] = Kept(value);
  }
  void Fill(const T& value) {
    if constexpr (FloatTexel<T>) {
      if (KeepsCodes()) {
        std::array<std::uint8_t, 4> texel{};
        EncodeCodes(*format_, value, texel.data(), codeChannels_);
        const std::size_t stride = CodeStride();
        if (std::all_of(texel.begin(), texel.begin() + codeChannels_, [&](std::uint8_t b) { return b == texel[0]; })) {
          std::memset(codes_.data(), texel[0], codes_.size());  // a clear: every byte the same
          return;
        }
        for (std::size_t at = 0; at < codes_.size(); at += stride) std::memcpy(codes_.data() + at, texel.data(), stride);
        return;
      }
    }
    std::fill(texels_.begin(), texels_.end(), Kept(value));
  }

 private:
  Texture2D(std::string name, int width, int height, int texelBytes, std::optional<Format> format)
      : Resource(CheckedName(std::move(name), width, height, texelBytes),
                 static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(texelBytes)),
        width_(width), height_(height), texelBytes_(texelBytes), format_(format) {
    if constexpr (FloatTexel<T>) {
      if (format && IsEightBitPerChannel(*format)) {
        codeChannels_ = Channels(*format);
        codes_.resize(TexelCount() * CodeStride());
      }
    }
  }
  static std::string CheckedName(std::string name, int width, int height, int texelBytes) {
    if (width < 1 || height < 1 || width > raster::kMaxDimension || height > raster::kMaxDimension) {
      throw std::invalid_argument("texture '" + name + "': size " + std::to_string(width) + "x" +
                                  std::to_string(height) + " outside 1.." +
                                  std::to_string(raster::kMaxDimension));
    }
    if (texelBytes < 1) throw std::invalid_argument("texture '" + name + "': texel size must be >= 1 byte");
    return name;
  }
  static std::string CheckedFormat(std::string name, Format format)
    requires FormattableTexel<T>
  {
    if (!CanHold<T>(format)) {
      throw std::invalid_argument("texture '" + name + "': its texel type cannot hold " +
                                  std::string(FormatName(format)));
    }
    return name;
  }
  std::size_t TexelCount() const { return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_); }
  std::size_t CodeStride() const { return static_cast<std::size_t>(codeChannels_); }
  T Kept(const T& value) const {
    if constexpr (FormattableTexel<T>) {
      if (format_) return Quantize(*format_, value);
    }
    return value;
  }

  int width_, height_, texelBytes_;
  std::optional<Format> format_;
  int codeChannels_ = 0;
  std::vector<T> texels_;
  std::vector<std::uint8_t> codes_;
};

template <typename T>
class Buffer : public Resource {
 public:
  Buffer(std::string name, std::size_t count, int elementBytes = sizeof(T), T fill = T{})
      : Resource(std::move(name), count * static_cast<std::size_t>(elementBytes)),
        elementBytes_(elementBytes), elements_(count, fill) {
    if (elementBytes < 1) throw std::invalid_argument("buffer '" + Name() + "': element size must be >= 1 byte");
  }

  std::size_t Size() const { return elements_.size(); }
  int ElementBytes() const { return elementBytes_; }
  T& At(std::size_t i) { return elements_[i]; }
  const T& At(std::size_t i) const { return elements_[i]; }
  std::span<T> Elements() { return elements_; }
  std::span<const T> Elements() const { return elements_; }

 private:
  int elementBytes_;
  std::vector<T> elements_;
};

// An append (structured) buffer: items plus a hidden 32-bit counter, as D3D's
// AppendStructuredBuffer. Appends made by one dispatch are committed in wave order after it, so
// item order is deterministic (the hardware's order is not; aa-facts §3 consumers do not depend
// on it). Appends past the capacity are dropped and counted as append/overflow.
template <typename T>
class AppendBuffer {
 public:
  AppendBuffer(std::string name, std::size_t capacity, int elementBytes = sizeof(T))
      : items_(name, capacity, elementBytes), counter_(name + "/counter", 1, 4) {}

  const std::string& Name() const { return items_.Name(); }
  std::size_t Capacity() const { return items_.Size(); }
  std::uint32_t Count() const { return counter_.At(0); }
  void ResetCounter() { counter_.At(0) = 0; }

  Buffer<T>& Storage() { return items_; }
  const Buffer<T>& Storage() const { return items_; }
  Buffer<std::uint32_t>& Counter() { return counter_; }
  const Buffer<std::uint32_t>& Counter() const { return counter_; }

 private:
  Buffer<T> items_;
  Buffer<std::uint32_t> counter_;
};

// The renderer's store of a linear frame into an RGBA8 sRGB render target (D3D11 §3.2.3.8, sRGB
// on RGB, alpha linear): what passes with an 8-bit colour input read. Host side, by rows on the
// worker threads (the result does not depend on the thread count); not a dispatch, so uncounted.
void StoreSrgb8(const Texture2D<glm::vec4>& linear, Texture2D<glm::vec4>& target);

}  // namespace sim
