#pragma once
// Typed resource views: the only way a kernel touches memory. Each access counts bytes, fetch
// instructions and atomics into the lane's chunk (a few integer adds) and marks the 64-byte lines
// it touched. Out-of-range loads return zero and out-of-range stores are dropped, as D3D UAV
// semantics require (aa-facts §3: the FXAA queue relies on dropped out-of-bounds writes); stores
// and appends from helper lanes are dropped, as the hardware masks them (hw-facts §6.1).
// Dropped out-of-range stores and atomics are counted per binding (stores_dropped_oob).
// Views are created by sim::Dispatch, which records the binding they count into.

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "raster/depth_stencil.h"
#include "sim/check.h"
#include "sim/lanes.h"
#include "sim/resources.h"

namespace sim {

namespace detail {
// A store another chunk of the same dispatch may also make to the same texel or element: D3D
// lets a dispatch's groups write one UAV location in any order (MiniEngine FXAA's luma tiles
// overlap by their apron, every group writing the same values there). Each scalar is stored
// with a relaxed atomic, which on x86 and ARM is the plain store, so such overlaps are not a
// host data race (ThreadSanitizer, docs/fuzzing.md). Overlapping writes of different values stay
// what they are on a GPU: an order-dependent result, which the determinism tests would catch.
template <typename T>
[[gnu::always_inline]] inline void StoreRelaxed(T& target, const T& value) {
  if constexpr (std::is_arithmetic_v<T>) {
    std::atomic_ref<T>(target).store(value, std::memory_order_relaxed);
  } else {
    for (glm::length_t c = 0; c < T::length(); ++c) {
      std::atomic_ref<typename T::value_type>(target[c]).store(value[c], std::memory_order_relaxed);
    }
  }
}

// The traffic a view counts into, after checking that the view belongs to the running dispatch.
inline ResourceTraffic& Traffic(const LaneBase& lane, const ViewBinding& binding) {
  CheckOrigin(lane, binding);
  AASIM_DCHECK_LT(static_cast<std::size_t>(binding.slot), lane.chunk->traffic.size());
  return lane.chunk->traffic[static_cast<std::size_t>(binding.slot)];
}
// A second binding of a view whose origin Traffic(lane, binding) has checked.
inline ResourceTraffic& Traffic(const LaneBase& lane, int slot) {
  AASIM_DCHECK_LT(static_cast<std::size_t>(slot), lane.chunk->traffic.size());
  return lane.chunk->traffic[static_cast<std::size_t>(slot)];
}

// The float filter's lerps, x then y: (t00 (1 - fx) + t10 fx) (1 - fy) + (t01 (1 - fx) + t11 fx) fy.
// A vec4 is blended as one 4-float vector: each lane is the same float32 multiply and add as the
// per-channel code (no contraction, -ffp-contract=off), the lerps in a quarter of the
// instructions; GCC does not vectorise glm's per-component operators here (docs/PERFORMANCE.md,
// "Stop 31"; SimViews.TheVectorBlendIsThePerChannelBlend).
template <typename T>
[[gnu::always_inline]] inline T BilinearBlend(const T& t00, const T& t10, const T& t01, const T& t11, glm::vec2 f) {
  if constexpr (std::is_same_v<T, glm::vec4>) {
    using Floats = float __attribute__((vector_size(16)));
    const auto load = [](const glm::vec4& v) {
      Floats out;
      std::memcpy(&out, &v, sizeof(out));
      return out;
    };
    const Floats top = load(t00) * (1.0f - f.x) + load(t10) * f.x;
    const Floats bottom = load(t01) * (1.0f - f.x) + load(t11) * f.x;
    const Floats blended = top * (1.0f - f.y) + bottom * f.y;
    glm::vec4 result;
    std::memcpy(&result, &blended, sizeof(result));
    return result;
  } else {
    const T top = t00 * (1.0f - f.x) + t10 * f.x;
    const T bottom = t01 * (1.0f - f.x) + t11 * f.x;
    return top * (1.0f - f.y) + bottom * f.y;
  }
}
}  // namespace detail

// How samplers address texels outside [0, 1): clamp to the edge, or wrap (glTF's default).
enum class AddressMode : std::uint8_t { Clamp, Repeat };

// Texel offsets of Load, Sample, SampleLevel and Gather range -8..7 per axis (d3d11.h
// D3D11_COMMONSHADER_TEXEL_OFFSET_MAX_NEGATIVE = -8, _MAX_POSITIVE = 7).
inline constexpr int kMinTexelOffset = -8;
inline constexpr int kMaxTexelOffset = 7;

namespace detail {
[[noreturn, gnu::noinline, gnu::cold]] inline void ThrowBadTexelArgument(const LaneBase& lane, const std::string& what) {
  throw KernelError(lane.chunk->dispatch->name + ": " + what);
}
[[noreturn, gnu::noinline, gnu::cold]] inline void ThrowBadTexelOffset(const LaneBase& lane, glm::ivec2 offset) {
  ThrowBadTexelArgument(lane, "texel offset (" + std::to_string(offset.x) + ", " + std::to_string(offset.y) +
                                  ") outside -8..7");
}
// The message is built out of line: every fetch inlines this check.
[[gnu::always_inline]] inline void CheckTexelOffset(const LaneBase& lane, glm::ivec2 offset) {
  const auto outside = [](int o) { return static_cast<unsigned>(o - kMinTexelOffset) > kMaxTexelOffset - kMinTexelOffset; };
  if (outside(offset.x) || outside(offset.y)) [[unlikely]] ThrowBadTexelOffset(lane, offset);
}
}  // namespace detail

// A texture read through a view format: the texture's own, or another of its typeless family
// (As). Loads and samples decode through the view format (an sRGB view returns linear values);
// a formatted UNORM8 view filters bilinearly in 8-bit fixed point, as llvmpipe does
// (sim/formats.h); everything else filters in float. Textures have no mips, so every sample
// reads level 0: HLSL's SampleLevel(s, uv, 0) and Sample(s, uv) are both SamplePoint or
// SampleBilinear here. Offsets are whole texels added to the texel index before addressing.
//
// A view keeps what every fetch needs (the texture's size, where its host texels or 8-bit codes
// are, how this view decodes them) so a fetch does no more than count, mark its lines and read.
template <typename T>
class TextureView {
 public:
  using Gathered = glm::vec<4, TexelScalar<T>>;

  TextureView(const Texture2D<T>& texture, ViewBinding binding)
      : texture_(&texture), binding_(std::move(binding)), format_(texture.TexelFormat()) {
    Cache();
  }

  // The same binding (same traffic counters, same bytes) read through another format: SMAA
  // reads one RGBA8 colour texture through a UNORM view and through an sRGB view (aa-facts §1.9).
  TextureView As(Format format) const {
    const std::optional<Format> resource = texture_->TexelFormat();
    if (!resource || !ViewCompatible(*resource, format)) {
      throw std::invalid_argument("texture '" + texture_->Name() + "': no " + std::string(FormatName(format)) +
                                  " view of a " + std::string(resource ? FormatName(*resource) : "format-less") +
                                  " texture");
    }
    TextureView view = *this;
    view.format_ = format;
    view.Cache();
    return view;
  }
  std::optional<Format> ViewFormat() const { return format_; }
  int Width() const { return width_; }
  int Height() const { return height_; }

  [[gnu::always_inline]] T Load(const LaneBase& lane, int x, int y, glm::ivec2 offset = {0, 0}) const {
    detail::CheckTexelOffset(lane, offset);
    CountFetch(lane, 1);
    x += offset.x;
    y += offset.y;
    if (!Contains(x, y)) return T{};  // D3D: out-of-range loads read zero
    const std::size_t index = Index(x, y);
    TouchTexel(index);
    return Decoded(index);
  }
  // uv in [0, 1] spans the texture; outside it the address mode applies.
  [[gnu::always_inline]] T SamplePoint(const LaneBase& lane, glm::vec2 uv, AddressMode mode = AddressMode::Clamp,
                glm::ivec2 offset = {0, 0}) const {
    detail::CheckTexelOffset(lane, offset);
    CountFetch(lane, 1);
    const glm::vec2 texel = uv * glm::vec2(width_, height_);
    const std::size_t index = Index(Address(static_cast<int>(std::floor(texel.x)) + offset.x, width_, mode),
                                    Address(static_cast<int>(std::floor(texel.y)) + offset.y, height_, mode));
    TouchTexel(index);
    return Decoded(index);
  }
  [[gnu::always_inline]] T SampleBilinear(const LaneBase& lane, glm::vec2 uv, AddressMode mode = AddressMode::Clamp,
                                          glm::ivec2 offset = {0, 0}) const {
    if constexpr (FloatTexel<T>) {
      if (filterUnorm8_) return SampleBilinearUnorm8(lane, uv, mode, offset);
    }
    return SampleBilinearFloat(lane, uv, mode, offset);
  }
  // Float weights on decoded texels, whatever the format. Texel centres at +0.5, the same
  // weights as scenes::SampleBilinearRepeat for Repeat.
  T SampleBilinearFloat(const LaneBase& lane, glm::vec2 uv, AddressMode mode = AddressMode::Clamp,
                        glm::ivec2 offset = {0, 0}) const {
    detail::CheckTexelOffset(lane, offset);
    CountFetch(lane, 4);
    const glm::vec2 texel = uv * glm::vec2(width_, height_) - 0.5f;
    const glm::vec2 base = glm::floor(texel);
    const glm::vec2 f = texel - base;
    const auto [xa, x1] = AddressPair(static_cast<int>(base.x) + offset.x, width_, mode);
    const auto [ya, y1] = AddressPair(static_cast<int>(base.y) + offset.y, height_, mode);
    TouchFootprint(xa, x1, ya, y1);
    // At a texel centre the lerps return the first texel exactly when every texel is finite, as
    // 8-bit texels always are; the footprint is still fetched.
    if (f.x == 0.0f && f.y == 0.0f && codes_ != nullptr) return Decoded(Index(xa, ya));
    return detail::BilinearBlend(Decoded(Index(xa, ya)), Decoded(Index(x1, ya)), Decoded(Index(xa, y1)),
                                 Decoded(Index(x1, y1)), f);
  }
  // The four texels of the bilinear footprint, one channel (0..3 = R..A; channels the format
  // lacks read 0, alpha 1), in D3D's gather4 order ("counter clockwise order starting with the
  // sample to the lower left", HLSL reference, gather4 (sm5 - asm); GLSL textureGather is the
  // same): x = (u0, v1), y = (u1, v1), z = (u1, v0), w = (u0, v0), v growing downwards. The
  // footprint is the float one (llvmpipe gathers on its float path, lp_bld_sample_soa.c).
  Gathered Gather(const LaneBase& lane, glm::vec2 uv, int channel = 0, glm::ivec2 offset = {0, 0},
                  AddressMode mode = AddressMode::Clamp) const {
    detail::CheckTexelOffset(lane, offset);
    if (channel < 0 || channel > 3) detail::ThrowBadTexelArgument(lane, "gather channel outside 0..3");
    CountFetch(lane, 4);
    const glm::vec2 texel = uv * glm::vec2(width_, height_) - 0.5f;
    const auto [u0, u1] = AddressPair(static_cast<int>(std::floor(texel.x)) + offset.x, width_, mode);
    const auto [v0, v1] = AddressPair(static_cast<int>(std::floor(texel.y)) + offset.y, height_, mode);
    const auto pick = [&](int x, int y) -> TexelScalar<T> {
      const std::size_t index = Index(x, y);
      TouchTexel(index);
      const T value = Decoded(index);
      if (channel < kTexelComponents<T>) return TexelComponent(value, channel);
      return channel == 3 ? TexelScalar<T>{1} : TexelScalar<T>{0};
    };
    return {pick(u0, v1), pick(u1, v1), pick(u1, v0), pick(u0, v0)};
  }

 private:
  template <typename>
  friend class RwTextureView;

  void Cache() {
    width_ = texture_->Width();
    height_ = texture_->Height();
    texelBytes_ = static_cast<std::size_t>(texture_->TexelBytes());
    AASIM_CHECK_LE(texelBytes_, static_cast<std::size_t>(kCacheLineBytes) / 2);  // TouchBytes marks a texel pair
    codeChannels_ = texture_->CodeChannels();
    codes_ = texture_->KeepsCodes() ? texture_->Codes().data() : nullptr;
    texels_ = texture_->KeepsCodes() ? nullptr : texture_->Texels().data();
    srgb_ = format_ == Format::RGBA8Srgb;
    fixedScale_ = {static_cast<float>(width_ * 256), static_cast<float>(height_ * 256)};
    readLines_ = texture_->ReadLines();
    filterUnorm8_ = format_ && IsUnorm8(*format_);
  }
  [[gnu::always_inline]] bool Contains(int x, int y) const {
    return static_cast<unsigned>(x) < static_cast<unsigned>(width_) &&
           static_cast<unsigned>(y) < static_cast<unsigned>(height_);
  }
  [[gnu::always_inline]] std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  [[gnu::always_inline]] static int Address(int i, int size, AddressMode mode) {
    if (mode == AddressMode::Clamp) [[likely]] return std::clamp(i, 0, size - 1);
    return Wrap(i, size);
  }
  // A footprint's two columns (or rows) i and i + 1 after addressing. Away from the edges they
  // are themselves in every mode: one unsigned compare instead of two clamps (or wraps).
  [[gnu::always_inline]] static std::pair<int, int> AddressPair(int i, int size, AddressMode mode) {
    if (static_cast<unsigned>(i) < static_cast<unsigned>(size - 1)) [[likely]] return {i, i + 1};
    return {Address(i, size, mode), Address(i + 1, size, mode)};
  }
  // Out of line: inlined, the compiler computes the division for every clamped coordinate too.
  [[gnu::noinline]] static int Wrap(int i, int size) {
    const int r = i % size;
    return r < 0 ? r + size : r;
  }
  // sim/formats.h ToFixedPointCoord and LerpUnorm8 on the 8-bit codes, in x then in y. The
  // texture keeps codes (a UNORM8 view is of an 8-bit texture); channels past the format's lerp
  // their default with itself.
  // Inlined into kernels: measured 10 % off SMAA's neighbourhood blend (three of these a pixel).
  [[gnu::always_inline]] T SampleBilinearUnorm8(const LaneBase& lane, glm::vec2 uv, AddressMode mode,
                                                glm::ivec2 offset) const {
    detail::CheckTexelOffset(lane, offset);
    CountFetch(lane, 4);
    const auto [cx, cy] = ToFixedPointCoordsScaled(uv, fixedScale_);
    const auto [xa, x1] = AddressPair(cx.texel + offset.x, width_, mode);
    const auto [ya, y1] = AddressPair(cy.texel + offset.y, height_, mode);
    TouchFootprint(xa, x1, ya, y1);
    // At a texel centre both weights are 0 and every lerp returns its first code: the stored
    // texel. The footprint is still fetched and counted.
    const std::uint32_t t00 = CodesWord(CodesAt(Index(xa, ya)), codeChannels_);
    if (cx.weight == 0 && cy.weight == 0) return DecodeWord<T>(t00, false);
    const std::uint32_t t10 = CodesWord(CodesAt(Index(x1, ya)), codeChannels_);
    const std::uint32_t t01 = CodesWord(CodesAt(Index(xa, y1)), codeChannels_);
    const std::uint32_t t11 = CodesWord(CodesAt(Index(x1, y1)), codeChannels_);
    const std::uint32_t top = LerpUnorm8Word(cx.weight, t00, t10), bottom = LerpUnorm8Word(cx.weight, t01, t11);
    return DecodeWord<T>(LerpUnorm8Word(cy.weight, top, bottom), false);
  }
  [[gnu::always_inline]] const std::uint8_t* CodesAt(std::size_t index) const {
    return codes_ + index * static_cast<std::size_t>(codeChannels_);
  }
  // One fetch instruction reading `texels` texels (the footprint; its lines are marked by Touch*).
  [[gnu::always_inline]] void CountFetch(const LaneBase& lane, int texels) const {
    ResourceTraffic& traffic = detail::Traffic(lane, binding_);
    ++traffic.fetches;
    traffic.bytesRead += static_cast<std::uint64_t>(texels) * texelBytes_;
  }
  [[gnu::always_inline]] void TouchTexel(std::size_t index) const {
    Resource::TouchBytes(readLines_, index * texelBytes_, texelBytes_);
  }
  // Columns x0 and x1 (equal, neighbours or wrapped) of row y, all inside the texture: the lines
  // their texels lie on, one range when they are neighbours in memory.
  [[gnu::always_inline]] void TouchRow(int x0, int x1, int y) const {
    const std::size_t first = Index(x0, y);
    if (x1 == x0 + 1) {
      Resource::TouchBytes(readLines_, first * texelBytes_, 2 * texelBytes_);
      return;
    }
    TouchTexel(first);
    if (x1 != x0) TouchTexel(Index(x1, y));
  }
  // A bilinear footprint's lines: the same as touching its four texels one by one.
  [[gnu::always_inline]] void TouchFootprint(int x0, int x1, int y0, int y1) const {
    TouchRow(x0, x1, y0);
    if (y1 != y0) TouchRow(x0, x1, y1);
  }
  // Texel `index` (inside the texture) as this view reads it.
  [[gnu::always_inline]] T Decoded(std::size_t index) const {
    if constexpr (FloatTexel<T>) {
      if (codes_ != nullptr) return DecodeCodes<T>(CodesAt(index), codeChannels_, srgb_);
    }
    return texels_[index];
  }

  const Texture2D<T>* texture_;
  ViewBinding binding_;
  std::optional<Format> format_;
  int width_ = 0, height_ = 0;
  std::size_t texelBytes_ = 0;
  // Where the host keeps the texels: an 8-bit texture's codes, or T.
  const std::uint8_t* codes_ = nullptr;
  int codeChannels_ = 0;
  const T* texels_ = nullptr;
  glm::vec2 fixedScale_{0.0f};  // ToFixedPointCoordScaled's scales
  std::uint64_t* readLines_ = nullptr;  // the texture's read-line bits (Resource::TouchRead)
  bool srgb_ = false;          // an sRGB view: RGB codes decode through the curve
  bool filterUnorm8_ = false;  // a UNORM8 view: bilinear in 8-bit fixed point
};

template <typename T>
class RwTextureView {
 public:
  RwTextureView(Texture2D<T>& texture, const ViewBinding& binding) : read_(texture, binding) { Cache(); }

  // The same binding through another format of its typeless family (TextureView::As): an sRGB
  // view of an RGBA8 texture encodes what it stores.
  RwTextureView As(Format format) const {
    RwTextureView view = *this;
    view.read_ = read_.As(format);
    return view;
  }
  std::optional<Format> ViewFormat() const { return read_.ViewFormat(); }
  int Width() const { return read_.Width(); }
  int Height() const { return read_.Height(); }
  [[gnu::always_inline]] T Load(const LaneBase& lane, int x, int y, glm::ivec2 offset = {0, 0}) const {
    return read_.Load(lane, x, y, offset);
  }
  // Quantised through the view format as the hardware's conversion does (sim/formats.h).
  [[gnu::always_inline]] void Store(const LaneBase& lane, int x, int y, const T& value) const {
    if (lane.helper) return;
    ResourceTraffic& traffic = detail::Traffic(lane, read_.binding_);
    if (!read_.Contains(x, y)) {
      ++traffic.storesDroppedOob;
      return;
    }
    const std::size_t index = read_.Index(x, y);
    traffic.bytesWritten += read_.texelBytes_;
    read_.texture_->TouchWrite(index * read_.texelBytes_, read_.texelBytes_);
    if constexpr (FloatTexel<T>) {
      if (codes_ != nullptr) {
        StoreCodes(index, EncodeWord(*read_.format_, value));
        return;
      }
    }
    detail::StoreRelaxed(texels_[index], Kept(value));
  }

 private:
  void Cache() {
    // The view reads what it writes: the same texture, so its storage is not const here.
    Texture2D<T>& texture = const_cast<Texture2D<T>&>(*read_.texture_);
    codes_ = texture.KeepsCodes() ? texture.Codes().data() : nullptr;
    texels_ = texture.KeepsCodes() ? nullptr : texture.Texels().data();
  }
  T Kept(const T& value) const {
    if constexpr (FormattableTexel<T>) {
      if (const std::optional<Format> format = read_.format_) return Quantize(*format, value);
    }
    return value;
  }
  // A texel's codes (channel 0 in the low byte of `word`) as one relaxed atomic store of its 1, 2
  // or 4 aligned bytes, as StoreRelaxed does for T.
  [[gnu::always_inline]] void StoreCodes(std::size_t index, std::uint32_t word) const {
    std::uint8_t* const at = codes_ + index * static_cast<std::size_t>(read_.codeChannels_);
    switch (read_.codeChannels_) {
      case 4:
        std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(at)).store(word, std::memory_order_relaxed);
        return;
      case 2:
        std::atomic_ref<std::uint16_t>(*reinterpret_cast<std::uint16_t*>(at))
            .store(static_cast<std::uint16_t>(word), std::memory_order_relaxed);
        return;
      default: std::atomic_ref<std::uint8_t>(*at).store(static_cast<std::uint8_t>(word), std::memory_order_relaxed);
    }
  }

  TextureView<T> read_;
  std::uint8_t* codes_ = nullptr;
  T* texels_ = nullptr;
};

template <typename T>
class BufferView {
 public:
  BufferView(const Buffer<T>& buffer, ViewBinding binding) : buffer_(&buffer), binding_(std::move(binding)) {}
  std::size_t Size() const { return buffer_->Size(); }
  T Load(const LaneBase& lane, std::size_t index) const {
    ResourceTraffic& traffic = detail::Traffic(lane, binding_);
    ++traffic.fetches;
    const auto bytes = static_cast<std::size_t>(buffer_->ElementBytes());
    traffic.bytesRead += bytes;
    if (index >= buffer_->Size()) return T{};
    buffer_->TouchRead(index * bytes, bytes);
    return buffer_->At(index);
  }

 private:
  const Buffer<T>* buffer_;
  ViewBinding binding_;
};

template <typename T>
class RwBufferView {
 public:
  RwBufferView(Buffer<T>& buffer, const ViewBinding& binding)
      : buffer_(&buffer), read_(buffer, binding), binding_(binding) {}
  std::size_t Size() const { return buffer_->Size(); }
  T Load(const LaneBase& lane, std::size_t index) const { return read_.Load(lane, index); }
  void Store(const LaneBase& lane, std::size_t index, const T& value) const {
    if (lane.helper) return;
    ResourceTraffic& traffic = detail::Traffic(lane, binding_);
    if (index >= buffer_->Size()) {
      ++traffic.storesDroppedOob;
      return;
    }
    const auto bytes = static_cast<std::size_t>(buffer_->ElementBytes());
    traffic.bytesWritten += bytes;
    buffer_->TouchWrite(index * bytes, bytes);
    detail::StoreRelaxed(buffer_->At(index), value);
  }
  // Atomics without a returned value (InterlockedAdd/Min/Max with no `original`): they commute,
  // so the result is the same whichever lane comes first, and any dispatch may use them.
  void AtomicAdd(const LaneBase& lane, std::size_t index, T value) const {
    Rmw(lane, index, [value](T old) { return static_cast<T>(old + value); });
  }
  void AtomicMin(const LaneBase& lane, std::size_t index, T value) const {
    Rmw(lane, index, [value](T old) { return std::min(old, value); });
  }
  void AtomicMax(const LaneBase& lane, std::size_t index, T value) const {
    Rmw(lane, index, [value](T old) { return std::max(old, value); });
  }
  // Atomics returning the value before the operation (`original` in HLSL). The value depends on
  // which lane came first, so only a dispatch whose chunks run serially may use them
  // (Dispatch::SerialChunks; a KernelError elsewhere). Helper lanes and out-of-range indices
  // change nothing and get 0 (D3D leaves that value undefined: SM5 imm_atomic_* remarks).
  T InterlockedAdd(const LaneBase& lane, std::size_t index, T value) const {
    detail::RequireSerialChunks(lane, "InterlockedAdd's returned value");
    return Rmw(lane, index, [value](T old) { return static_cast<T>(old + value); });
  }
  T InterlockedMin(const LaneBase& lane, std::size_t index, T value) const {
    detail::RequireSerialChunks(lane, "InterlockedMin's returned value");
    return Rmw(lane, index, [value](T old) { return std::min(old, value); });
  }
  T InterlockedMax(const LaneBase& lane, std::size_t index, T value) const {
    detail::RequireSerialChunks(lane, "InterlockedMax's returned value");
    return Rmw(lane, index, [value](T old) { return std::max(old, value); });
  }
  T InterlockedExchange(const LaneBase& lane, std::size_t index, T value) const {
    detail::RequireSerialChunks(lane, "InterlockedExchange");
    return Rmw(lane, index, [value](T) { return value; });
  }
  // Stores `value` only where the element equals `compare`.
  T InterlockedCompareExchange(const LaneBase& lane, std::size_t index, T compare, T value) const {
    detail::RequireSerialChunks(lane, "InterlockedCompareExchange");
    return Rmw(lane, index, [compare, value](T old) { return old == compare ? value : old; });
  }

 private:
  // One atomic read-modify-write; returns the value before it, or 0 when dropped.
  template <typename Op>
  T Rmw(const LaneBase& lane, std::size_t index, Op op) const {
    static_assert(std::is_integral_v<T>, "atomics are defined on integer buffers");
    if (lane.helper) return T{};
    ResourceTraffic& traffic = detail::Traffic(lane, binding_);
    if (index >= buffer_->Size()) {
      ++traffic.storesDroppedOob;
      return T{};
    }
    const auto bytes = static_cast<std::size_t>(buffer_->ElementBytes());
    ++traffic.atomics;
    buffer_->TouchWrite(index * bytes, bytes);
    std::atomic_ref<T> element(buffer_->At(index));
    T old = element.load(std::memory_order_relaxed);
    while (!element.compare_exchange_weak(old, op(old), std::memory_order_relaxed)) {
    }
    return old;
  }

  Buffer<T>* buffer_;
  BufferView<T> read_;
  ViewBinding binding_;
};

// Append without a returned index (D3D AppendStructuredBuffer::Append). Each append is one
// atomic on the hidden counter and one element written; items are committed after the dispatch.
template <typename T>
class AppendView {
 public:
  AppendView(ViewBinding items, int counterSlot, int stagingIndex, int elementBytes)
      : items_(std::move(items)), counterSlot_(counterSlot), stagingIndex_(stagingIndex), elementBytes_(elementBytes) {}

  void Append(const LaneBase& lane, const T& value) const {
    static_assert(std::is_trivially_copyable_v<T>);
    if (lane.helper) return;
    detail::Traffic(lane, items_).bytesWritten += static_cast<std::uint64_t>(elementBytes_);
    ++detail::Traffic(lane, counterSlot_).atomics;
    std::vector<std::byte>& staging = lane.chunk->appends[static_cast<std::size_t>(stagingIndex_)];
    const std::size_t at = staging.size();
    staging.resize(at + sizeof(T));
    std::memcpy(staging.data() + at, &value, sizeof(T));
  }

 private:
  ViewBinding items_;
  int counterSlot_, stagingIndex_, elementBytes_;
};

// Increments a pass counter the dispatch declared (Dispatch::Counter): counted per chunk and
// merged in chunk order, like traffic. Helper lanes do not count, as their stores do not land.
class CounterView {
 public:
  explicit CounterView(ViewBinding counter) : counter_(std::move(counter)) {}

  void Add(const LaneBase& lane, std::uint64_t n = 1) const {
    detail::CheckOrigin(lane, counter_);
    if (lane.helper) return;
    lane.chunk->passCounters[static_cast<std::size_t>(counter_.slot)] += n;
  }

 private:
  ViewBinding counter_;  // slot: the counter's index in the dispatch
};

// A stencil target for post passes: a one-sample depth/stencil surface whose per-pixel stencil a
// pixel kernel exports and whose hi-stencil tile bits (hw-facts §5.3) a later full-screen pass
// uses to drop tiles.
class StencilBuffer : public Resource {
 public:
  StencilBuffer(std::string name, int width, int height);
  raster::DepthStencilSurface& Surface() { return surface_; }
  const raster::DepthStencilSurface& Surface() const { return surface_; }
  int Width() const { return surface_.Config().width; }
  int Height() const { return surface_.Config().height; }
  void Clear(std::uint8_t value);

 private:
  raster::DepthStencilSurface surface_;
};

// Stencil export from a pixel kernel (the DB's stencil write). Only pixel dispatches may bind it:
// bins own their 8x8 tiles, so hi-stencil refreshes never race.
class StencilView {
 public:
  StencilView(StencilBuffer& stencil, ViewBinding binding) : stencil_(&stencil), binding_(std::move(binding)) {}
  void Store(const PixelLane& lane, std::uint8_t value) const {
    if (lane.helper || lane.x >= stencil_->Width() || lane.y >= stencil_->Height()) return;
    detail::Traffic(lane, binding_).bytesWritten += 1;
    stencil_->TouchWrite(static_cast<std::size_t>(lane.y) * static_cast<std::size_t>(stencil_->Width()) +
                             static_cast<std::size_t>(lane.x),
                         1);
    stencil_->Surface().SetStencil(lane.x, lane.y, value);
  }

 private:
  StencilBuffer* stencil_;
  ViewBinding binding_;
};

}  // namespace sim
