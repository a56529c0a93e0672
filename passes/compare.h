#pragma once
// The one rule for "the strategies agree" (DESIGN.md: images are bit-identical across
// strategies): every strategy's output colour and every layer, bit for bit, against the first
// strategy's, plus the same work-set size. Bitwise, so -0 against +0 or two NaN payloads count.

#include <cstdint>
#include <cstring>
#include <span>
#include <string>

#include "passes/pass.h"

namespace passes {

// Where two same-sized images differ bit for bit: how many pixels, and the first in row order.
struct ImageDifference {
  std::uint64_t pixels = 0;
  int x = 0, y = 0;
};

template <typename T>
ImageDifference BitwiseDifference(const sim::Texture2D<T>& a, const sim::Texture2D<T>& b) {
  ImageDifference difference;
  for (int y = 0; y < a.Height(); ++y) {
    for (int x = 0; x < a.Width(); ++x) {
      const T left = a.Get(x, y), right = b.Get(x, y);
      if (std::memcmp(&left, &right, sizeof(T)) == 0) continue;
      if (difference.pixels++ == 0) {
        difference.x = x;
        difference.y = y;
      }
    }
  }
  return difference;
}

struct StrategyDifference {
  std::string what;  // "" when identical, else "output", a layer name, or "work items"
  ImageDifference pixels;
  bool Identical() const { return what.empty(); }
  // "identical" or "output differs in 12 pixels, first at (3, 4)".
  std::string Describe() const;
};

// The first difference of `other` from `first`: output colour, then the layers in order, then
// the work-set size.
StrategyDifference CompareOutputs(const PassOutput& first, const PassOutput& other);

}  // namespace passes
