#pragma once
// FXAA 3.11 "PC quality" (NVIDIA Fxaa3_11.h by Timothy Lottes, FXAA_PC 1, FXAA_GREEN_AS_LUMA 0,
// FXAA_DISCARD 0) as kernels on the machine, in the header's float32 order: every product and
// sum of FxaaPixelShader is one rounding, as on the measured path (aa-facts §1.9; passes/ is
// compiled without FP contraction). The header's luma pre-pass example, the early exit and the
// rest of the shader are three separate functions so the early exit can be the work set's detect.
//
// Fetches are the header's: FxaaTexTop/FxaaTexOff at the pixel centre and whole-texel offsets
// (exact texels: a bilinear fetch at a texel centre is the texel), bilinear luma fetches at the
// search positions and one bilinear colour fetch at the final position, all on an RGBA8 UNORM
// texture through the machine's fixed-point bilinear (sim/formats.h, aa-facts §1.9), clamp
// addressing. pos = ((x + 0.5) / W, (y + 0.5) / H) in float32, as SMAA's kernels compute their
// texcoord (passes/smaa/smaa_kernels.h says why per pixel and not interpolated).

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "sim/views.h"

namespace passes::fxaa {

// FXAA_QUALITY__PS and FXAA_QUALITY__P0..P11 of one FXAA_QUALITY__PRESET (Fxaa3_11.h "FXAA
// QUALITY - PRESETS"): the search's step lengths in pixels, P0 to the first luma fetch on each
// side, the last one the distance assumed when no end was found.
struct StepTable {
  int preset = 0;
  int count = 0;  // FXAA_QUALITY__PS
  std::array<float, 12> steps{};

  std::span<const float> Steps() const { return {steps.data(), static_cast<std::size_t>(count)}; }
};

// Every preset of the header: 10-15 "medium dither", 20-29 "low dither", 39 "no dither".
inline constexpr std::array<StepTable, 17> kStepTables{{
    {10, 3, {1.5f, 3.0f, 12.0f}},
    {11, 4, {1.0f, 1.5f, 3.0f, 12.0f}},
    {12, 5, {1.0f, 1.5f, 2.0f, 4.0f, 12.0f}},
    {13, 6, {1.0f, 1.5f, 2.0f, 2.0f, 4.0f, 12.0f}},
    {14, 7, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
    {15, 8, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
    {20, 3, {1.5f, 2.0f, 8.0f}},
    {21, 4, {1.0f, 1.5f, 2.0f, 8.0f}},
    {22, 5, {1.0f, 1.5f, 2.0f, 2.0f, 8.0f}},
    {23, 6, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 8.0f}},
    {24, 7, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 3.0f, 8.0f}},
    {25, 8, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
    {26, 9, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
    {27, 10, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
    {28, 11, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
    {29, 12, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
    {39, 12, {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
}};

// FXAA_QUALITY__PRESET's default (Fxaa3_11.h "FXAA QUALITY - TUNING KNOBS").
inline constexpr int kDefaultPreset = 12;

inline const StepTable* FindStepTable(int preset) {
  const auto* found = std::find_if(kStepTables.begin(), kStepTables.end(),
                                   [&](const StepTable& table) { return table.preset == preset; });
  return found == kStepTables.end() ? nullptr : found;
}

// The header's integration example (Fxaa3_11.h "INTEGRATION - RGBL AND COLORSPACE"): luma =
// dot(rgb, (0.299, 0.587, 0.114)) of the gamma-space colour, evaluated as x*wx + (y*wy + z*wz)
// as llvmpipe's dot (aa-facts §1.9); the RGBA8 store rounds it to 8 bits.
inline float PrepassLuma(const glm::vec3& gamma) { return gamma.x * 0.299f + (gamma.y * 0.587f + gamma.z * 0.114f); }

// FxaaPixelShader's inputs besides the texture: fxaaQualityRcpFrame, fxaaQualitySubpix,
// fxaaQualityEdgeThreshold, fxaaQualityEdgeThresholdMin and the compiled-in step table.
struct Params {
  int width = 1, height = 1;
  float subpix = 0.75f;
  float edgeThreshold = 0.166f;
  float edgeThresholdMin = 0.0833f;
  StepTable table = *FindStepTable(kDefaultPreset);

  glm::vec2 RcpFrame() const { return {1.0f / static_cast<float>(width), 1.0f / static_cast<float>(height)}; }
  glm::vec2 Pos(int x, int y) const {
    return {(static_cast<float>(x) + 0.5f) / static_cast<float>(width),
            (static_cast<float>(y) + 0.5f) / static_cast<float>(height)};
  }
};

// The early exit's inputs: the centre texel and its four neighbours' lumas.
struct Cross {
  glm::vec4 rgbyM{0.0f};
  float lumaN = 0.0f, lumaS = 0.0f, lumaE = 0.0f, lumaW = 0.0f;
  float range = 0.0f;
  bool earlyExit = true;

  float LumaM() const { return rgbyM.w; }
};

// What the edge part decided, for inspection: the span's direction, the search's reach on each
// side (in pixels from the centre) and the offset it sampled at.
struct Span {
  bool horizontal = false;
  float dstN = 0.0f, dstP = 0.0f;  // in texture-space units, as the shader computes them
  float pixelOffset = 0.0f;        // pixelOffsetSubpix, negative towards N (or W), positive towards S (or E)
  int fetches = 0;                 // bilinear luma fetches of the search, both sides
};

struct EdgeResult {
  glm::vec4 colour{0.0f};  // float4(FxaaTexTop(tex, posM).xyz, lumaM)
  Span span;
};

class FxaaQuality {
 public:
  FxaaQuality(const Params& params, sim::TextureView<glm::vec4> rgbl) : params_(params), rgbl_(std::move(rgbl)) {}

  // FxaaPixelShader up to `if (earlyExit) return rgbyM;`.
  Cross Contrast(const sim::LaneBase& lane, int x, int y) const;
  // The rest of FxaaPixelShader, for a pixel whose Contrast did not exit early.
  EdgeResult Edge(const sim::LaneBase& lane, int x, int y, const Cross& cross) const;

 private:
  // FxaaTexOff at the pixel centre: the (clamped) neighbour's texel. Inlined: called, it returned
  // the vec4 through the stack on every fetch (docs/PERFORMANCE.md, "Stop 28").
  [[gnu::always_inline]] glm::vec4 Texel(const sim::LaneBase& lane, int x, int y) const {
    return rgbl_.Load(lane, std::clamp(x, 0, rgbl_.Width() - 1), std::clamp(y, 0, rgbl_.Height() - 1));
  }
  float Luma(const sim::LaneBase& lane, int x, int y) const { return Texel(lane, x, y).w; }
  // FxaaTexTop at a search position: bilinear, alpha.
  float LumaAt(const sim::LaneBase& lane, glm::vec2 pos) const { return rgbl_.SampleBilinear(lane, pos).w; }

  Params params_;
  sim::TextureView<glm::vec4> rgbl_;
};

inline Cross FxaaQuality::Contrast(const sim::LaneBase& lane, int x, int y) const {
  Cross c;
  c.rgbyM = Texel(lane, x, y);
  c.lumaS = Luma(lane, x, y + 1);
  c.lumaE = Luma(lane, x + 1, y);
  c.lumaN = Luma(lane, x, y - 1);
  c.lumaW = Luma(lane, x - 1, y);
  const float lumaM = c.LumaM();
  const float maxSM = std::max(c.lumaS, lumaM), minSM = std::min(c.lumaS, lumaM);
  const float maxESM = std::max(c.lumaE, maxSM), minESM = std::min(c.lumaE, minSM);
  const float maxWN = std::max(c.lumaN, c.lumaW), minWN = std::min(c.lumaN, c.lumaW);
  const float rangeMax = std::max(maxWN, maxESM), rangeMin = std::min(minWN, minESM);
  const float rangeMaxScaled = rangeMax * params_.edgeThreshold;
  c.range = rangeMax - rangeMin;
  const float rangeMaxClamped = std::max(params_.edgeThresholdMin, rangeMaxScaled);
  c.earlyExit = c.range < rangeMaxClamped;
  return c;
}

inline EdgeResult FxaaQuality::Edge(const sim::LaneBase& lane, int x, int y, const Cross& cross) const {
  const glm::vec2 rcpFrame = params_.RcpFrame();
  glm::vec2 posM = params_.Pos(x, y);
  const float lumaM = cross.LumaM();
  float lumaN = cross.lumaN, lumaS = cross.lumaS;
  const float lumaNW = Luma(lane, x - 1, y - 1), lumaSE = Luma(lane, x + 1, y + 1);
  const float lumaNE = Luma(lane, x + 1, y - 1), lumaSW = Luma(lane, x - 1, y + 1);

  // Horizontal or vertical span: second differences across each axis, the centre's weighted 2x.
  const float lumaNS = lumaN + lumaS, lumaWE = cross.lumaW + cross.lumaE;
  const float subpixRcpRange = 1.0f / cross.range;
  const float subpixNSWE = lumaNS + lumaWE;
  const float edgeHorz1 = (-2.0f * lumaM) + lumaNS, edgeVert1 = (-2.0f * lumaM) + lumaWE;
  const float lumaNESE = lumaNE + lumaSE, lumaNWNE = lumaNW + lumaNE;
  const float edgeHorz2 = (-2.0f * cross.lumaE) + lumaNESE, edgeVert2 = (-2.0f * lumaN) + lumaNWNE;
  const float lumaNWSW = lumaNW + lumaSW, lumaSWSE = lumaSW + lumaSE;
  const float edgeHorz4 = (std::fabs(edgeHorz1) * 2.0f) + std::fabs(edgeHorz2);
  const float edgeVert4 = (std::fabs(edgeVert1) * 2.0f) + std::fabs(edgeVert2);
  const float edgeHorz3 = (-2.0f * cross.lumaW) + lumaNWSW, edgeVert3 = (-2.0f * lumaS) + lumaSWSE;
  const float edgeHorz = std::fabs(edgeHorz3) + edgeHorz4, edgeVert = std::fabs(edgeVert3) + edgeVert4;

  const float subpixNWSWNESE = lumaNWSW + lumaNESE;
  float lengthSign = rcpFrame.x;
  const bool horzSpan = edgeHorz >= edgeVert;
  const float subpixA = subpixNSWE * 2.0f + subpixNWSWNESE;
  if (!horzSpan) lumaN = cross.lumaW;
  if (!horzSpan) lumaS = cross.lumaE;
  if (horzSpan) lengthSign = rcpFrame.y;
  const float subpixB = (subpixA * (1.0f / 12.0f)) - lumaM;

  // The steeper side of the pair across the span: the edge lies between M and that neighbour.
  const float gradientN = lumaN - lumaM, gradientS = lumaS - lumaM;
  float lumaNN = lumaN + lumaM;
  const float lumaSS = lumaS + lumaM;
  const bool pairN = std::fabs(gradientN) >= std::fabs(gradientS);
  const float gradient = std::max(std::fabs(gradientN), std::fabs(gradientS));
  if (pairN) lengthSign = -lengthSign;
  const float subpixC = std::clamp(std::fabs(subpixB) * subpixRcpRange, 0.0f, 1.0f);

  // The search runs on the edge line, half a pixel towards the pair, in both directions.
  glm::vec2 posB = posM;
  const glm::vec2 offNP(!horzSpan ? 0.0f : rcpFrame.x, horzSpan ? 0.0f : rcpFrame.y);
  if (!horzSpan) posB.x += lengthSign * 0.5f;
  if (horzSpan) posB.y += lengthSign * 0.5f;

  const std::span<const float> steps = params_.table.Steps();
  glm::vec2 posN(posB.x - offNP.x * steps[0], posB.y - offNP.y * steps[0]);
  glm::vec2 posP(posB.x + offNP.x * steps[0], posB.y + offNP.y * steps[0]);
  const float subpixD = ((-2.0f) * subpixC) + 3.0f;
  float lumaEndN = LumaAt(lane, posN);
  const float subpixE = subpixC * subpixC;
  float lumaEndP = LumaAt(lane, posP);
  int fetches = 2;

  if (!pairN) lumaNN = lumaSS;
  const float gradientScaled = gradient * 1.0f / 4.0f;
  const float lumaMM = lumaM - lumaNN * 0.5f;
  const float subpixF = subpixD * subpixE;
  const bool lumaMLTZero = lumaMM < 0.0f;

  // An end is a sample whose luma left the pair's average by a quarter of the gradient.
  lumaEndN -= lumaNN * 0.5f;
  lumaEndP -= lumaNN * 0.5f;
  bool doneN = std::fabs(lumaEndN) >= gradientScaled;
  bool doneP = std::fabs(lumaEndP) >= gradientScaled;
  const auto stepOut = [&](float step) {
    if (!doneN) posN.x -= offNP.x * step;
    if (!doneN) posN.y -= offNP.y * step;
    if (!doneP) posP.x += offNP.x * step;
    if (!doneP) posP.y += offNP.y * step;
  };
  stepOut(steps[1]);
  bool doneNP = (!doneN) || (!doneP);
  // The header's nested `#if (FXAA_QUALITY__PS > i) if (doneNP) { ... }` blocks, one per step.
  for (std::size_t i = 2; i < steps.size() && doneNP; ++i) {
    if (!doneN) lumaEndN = LumaAt(lane, posN);
    if (!doneP) lumaEndP = LumaAt(lane, posP);
    fetches += (!doneN ? 1 : 0) + (!doneP ? 1 : 0);
    if (!doneN) lumaEndN = lumaEndN - lumaNN * 0.5f;
    if (!doneP) lumaEndP = lumaEndP - lumaNN * 0.5f;
    doneN = std::fabs(lumaEndN) >= gradientScaled;
    doneP = std::fabs(lumaEndP) >= gradientScaled;
    stepOut(steps[i]);
    doneNP = (!doneN) || (!doneP);
  }

  float dstN = posM.x - posN.x, dstP = posP.x - posM.x;
  if (!horzSpan) dstN = posM.y - posN.y;
  if (!horzSpan) dstP = posP.y - posM.y;

  // Blend towards the pair by the distance to the nearer end, if that end's luma moved the way
  // the centre's did; at least by the sub-pixel amount.
  const bool goodSpanN = (lumaEndN < 0.0f) != lumaMLTZero;
  const float spanLength = dstP + dstN;
  const bool goodSpanP = (lumaEndP < 0.0f) != lumaMLTZero;
  const float spanLengthRcp = 1.0f / spanLength;
  const bool directionN = dstN < dstP;
  const float dst = std::min(dstN, dstP);
  const bool goodSpan = directionN ? goodSpanN : goodSpanP;
  const float subpixG = subpixF * subpixF;
  const float pixelOffset = (dst * (-spanLengthRcp)) + 0.5f;
  const float subpixH = subpixG * params_.subpix;
  const float pixelOffsetGood = goodSpan ? pixelOffset : 0.0f;
  const float pixelOffsetSubpix = std::max(pixelOffsetGood, subpixH);
  if (!horzSpan) posM.x += pixelOffsetSubpix * lengthSign;
  if (horzSpan) posM.y += pixelOffsetSubpix * lengthSign;
  const glm::vec4 rgb = rgbl_.SampleBilinear(lane, posM);
  return {{rgb.x, rgb.y, rgb.z, lumaM},
          {.horizontal = horzSpan, .dstN = dstN, .dstP = dstP, .pixelOffset = lengthSign < 0.0f ? -pixelOffsetSubpix : pixelOffsetSubpix, .fetches = fetches}};
}

}  // namespace passes::fxaa
