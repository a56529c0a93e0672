// The FMASK layout table of hw-facts §1.1 and the per-sample code accessors.

#include "fmask/layout.h"

#include <stdexcept>

namespace fmask {
namespace {

struct LegalLayout {
  int samples, fragments, bitsPerSample, elementBits;
};

// hw-facts §1.1 (ADDR HwlComputeFmaskBits; FMASK{bpp}_S{S}_F{F} descriptor formats).
constexpr LegalLayout kLegal[] = {
    {2, 1, 1, 8},   {2, 2, 1, 8},                                    //
    {4, 1, 1, 8},   {4, 2, 2, 8},   {4, 4, 2, 8},                    //
    {8, 1, 1, 8},   {8, 2, 2, 16},  {8, 4, 4, 32},  {8, 8, 4, 32},   //
    {16, 1, 1, 16}, {16, 2, 2, 32}, {16, 4, 4, 64}, {16, 8, 4, 64},
};

std::string LegalList() {
  std::string list;
  for (const LegalLayout& l : kLegal) {
    list += (list.empty() ? "" : ", ") + std::to_string(l.samples) + "S" + std::to_string(l.fragments) + "F";
  }
  return list;
}

}  // namespace

FmaskLayout FmaskLayout::For(int coverageSamples, int fragments) {
  // hw-facts §1.1 has FMASK only for 2+ samples: a single-sample surface keeps its one fragment
  // and needs no codes, so its layout stores nothing (every sample reads fragment 0).
  if (coverageSamples == 1 && fragments == 1) return FmaskLayout(1, 1, 0, 0);
  for (const LegalLayout& l : kLegal) {
    if (l.samples == coverageSamples && l.fragments == fragments) {
      return FmaskLayout(l.samples, l.fragments, l.bitsPerSample, l.elementBits);
    }
  }
  throw std::invalid_argument("no FMASK layout for " + std::to_string(coverageSamples) + " samples and " +
                              std::to_string(fragments) + " fragments; legal: " + LegalList());
}

std::vector<FmaskLayout> FmaskLayout::AllLegal() {
  std::vector<FmaskLayout> all;
  for (const LegalLayout& l : kLegal) all.push_back(For(l.samples, l.fragments));
  return all;
}

std::string FmaskLayout::FormatName() const {
  if (elementBits_ == 0) return "none";
  return "FMASK" + std::to_string(elementBits_) + "_S" + std::to_string(samples_) + "_F" +
         std::to_string(fragments_);
}

int FmaskLayout::Code(FmaskElement element, int sample) const {
  const FmaskElement mask = (FmaskElement{1} << bitsPerSample_) - 1;
  return static_cast<int>((element >> (sample * bitsPerSample_)) & mask);
}

FmaskElement FmaskLayout::WithCode(FmaskElement element, int sample, int code) const {
  const int shift = sample * bitsPerSample_;
  const FmaskElement mask = ((FmaskElement{1} << bitsPerSample_) - 1) << shift;
  return (element & ~mask) | ((static_cast<FmaskElement>(code) << shift) & mask);
}

FmaskElement FmaskLayout::ExpandedValue() const {
  FmaskElement value = 0;
  for (int s = 0; s < samples_; ++s) value = WithCode(value, s, s < fragments_ ? s : fragments_);
  return value;
}

std::uint64_t ShaderVisibleMask(const FmaskLayout& layout, FmaskElement element) {
  std::uint64_t visible = 0;
  for (int s = 0; s < layout.CoverageSamples(); ++s) {
    const int code = layout.Code(element, s);
    const bool unknown = layout.IsEqaa() && code == layout.UnknownCode();
    visible |= static_cast<std::uint64_t>(unknown ? kShaderVisibleUnknown : code) << (4 * s);
  }
  return visible;
}

}  // namespace fmask
