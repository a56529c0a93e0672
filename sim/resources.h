#pragma once
// Memory the kernels read and write: 2D textures, buffers and append buffers with their atomic
// counter. Each resource knows its modelled size in bytes (the format the hardware would store,
// not the float the host keeps) and records which 64-byte lines a dispatch touched, so traffic is
// reported both as lane requests and as distinct lines (sim/counters.h ResourceTraffic).
// Host access (At, Fill) is not counted: only views (sim/views.h) count.

#include <atomic>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/limits.h"
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
  std::uint64_t LinesWritten() const { return CountBits(writtenLines_); }

 private:
  static void Touch(std::vector<std::uint64_t>& lines, std::size_t byteOffset, std::size_t bytes);
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
  for (std::size_t line = first; line <= last; ++line) {
    std::uint64_t& word = lines[line / 64];
    const std::uint64_t bit = std::uint64_t{1} << (line % 64);
    std::atomic_ref<std::uint64_t> ref(word);
    // Most touches hit a line already seen: a relaxed load avoids the locked OR.
    if ((ref.load(std::memory_order_relaxed) & bit) == 0) ref.fetch_or(bit, std::memory_order_relaxed);
  }
}

// Row-major texels. Without a Format the host keeps T unchanged and texelBytes is only the
// modelled size (e.g. 4 for RGBA8 even though the host keeps float RGBA). With a Format
// (sim/formats.h) the size comes from it and every texel is kept as its views read it: stores
// through views, Fill and the fill value are quantised; At() is the raw host value.
template <typename T>
class Texture2D : public Resource {
 public:
  Texture2D(std::string name, int width, int height, int texelBytes = sizeof(T), T fill = T{})
      : Resource(CheckedName(std::move(name), width, height, texelBytes),
                 static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                     static_cast<std::size_t>(texelBytes)),
        width_(width), height_(height), texelBytes_(texelBytes),
        texels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill) {}
  Texture2D(std::string name, int width, int height, Format format, T fill = T{})
    requires FormattableTexel<T>
      : Texture2D(CheckedFormat(std::move(name), format), width, height, BytesPerTexel(format)) {
    format_ = format;
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
  T& At(int x, int y) { return texels_[Index(x, y)]; }
  const T& At(int x, int y) const { return texels_[Index(x, y)]; }
  std::span<T> Texels() { return texels_; }
  std::span<const T> Texels() const { return texels_; }
  void Fill(const T& value) { std::fill(texels_.begin(), texels_.end(), Kept(value)); }

 private:
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
  T Kept(const T& value) const {
    if constexpr (FormattableTexel<T>) {
      if (format_) return Quantize(*format_, value);
    }
    return value;
  }

  int width_, height_, texelBytes_;
  std::optional<Format> format_;
  std::vector<T> texels_;
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

}  // namespace sim
