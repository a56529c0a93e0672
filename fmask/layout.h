#pragma once
// FMASK storage as GCN lays it out (hw-facts §1): which (S coverage samples, F fragments)
// combinations exist, bits per sample code, the per-pixel element size, the UNKNOWN code, the
// "fully expanded" and fast-cleared states, and the shader-visible 4-bit-per-sample form.

#include <cstdint>
#include <string>
#include <vector>

namespace fmask {

using FmaskElement = std::uint64_t;  // one pixel; only the low ElementBits() bits are used

class FmaskLayout {
 public:
  // Throws std::invalid_argument listing the legal combinations when (S, F) does not exist.
  // (1, 1) is the single-sample surface: no FMASK (0 bits), every sample reads fragment 0.
  static FmaskLayout For(int coverageSamples, int fragments);
  // The hardware FMASK layouts (S >= 2), without the single-sample (1, 1).
  static std::vector<FmaskLayout> AllLegal();

  int CoverageSamples() const { return samples_; }
  int Fragments() const { return fragments_; }
  int BitsPerSample() const { return bitsPerSample_; }
  int ElementBits() const { return elementBits_; }
  bool IsEqaa() const { return fragments_ < samples_; }
  // hw-facts §1.3: UNKNOWN is stored as the code F; MSAA (F == S) has no UNKNOWN.
  int UnknownCode() const { return fragments_; }
  std::string FormatName() const;  // e.g. "FMASK32_S8_F4" (hw-facts §1.1); "none" for (1, 1)

  int Code(FmaskElement element, int sample) const;
  FmaskElement WithCode(FmaskElement element, int sample, int code) const;
  // hw-facts §1.3: sample i -> min(i, F), what PAL and radeonsi write to initialise FMASK.
  FmaskElement ExpandedValue() const;
  // hw-facts §1.5: a fast-cleared surface reads as every sample -> fragment 0.
  static constexpr FmaskElement ClearedValue() { return 0; }

 private:
  FmaskLayout(int samples, int fragments, int bitsPerSample, int elementBits)
      : samples_(samples), fragments_(fragments), bitsPerSample_(bitsPerSample), elementBits_(elementBits) {}

  int samples_, fragments_, bitsPerSample_, elementBits_;
};

// hw-facts §1.2-§1.3: what fragmentMaskFetchAMD returns: nibble i = fragment of sample i, an
// UNKNOWN sample reported as 8. Only the first 8 samples fit in 32 bits; for 16 samples the
// 64-bit form is returned (how the texture unit packs 16 samples is not public, §9).
std::uint64_t ShaderVisibleMask(const FmaskLayout& layout, FmaskElement element);
inline constexpr int kShaderVisibleUnknown = 8;

// hw-facts §1.4: Mesa's fetch takes 3 bits of the nibble, so UNKNOWN (8) reads fragment 0.
constexpr int FetchFragmentIndex(std::uint64_t shaderVisibleMask, int sample) {
  return static_cast<int>((shaderVisibleMask >> (4 * sample)) & 7u);
}

}  // namespace fmask
