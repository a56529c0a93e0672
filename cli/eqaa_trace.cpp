// Colour-block trace files (see eqaa_trace.h).

#include "cli/eqaa_trace.h"

#include <cstdio>
#include <vector>

namespace cli {
namespace {

const char* CauseName(fmask::UnknownCause cause) {
  switch (cause) {
    case fmask::UnknownCause::None: return "none";
    case fmask::UnknownCause::Initial: return "initial";
    case fmask::UnknownCause::Eviction: return "eviction";
    case fmask::UnknownCause::Untestable: return "untestable";
  }
  return "?";
}

// "0x" and ElementBits / 4 digits, so the width shows which FMASK format it is.
std::string ElementHex(const fmask::FmaskLayout& layout, fmask::FmaskElement element) {
  char text[24];
  std::snprintf(text, sizeof(text), "0x%0*llx", layout.ElementBits() / 4,
                static_cast<unsigned long long>(element));
  return text;
}

std::vector<int> Codes(const fmask::FmaskLayout& layout, fmask::FmaskElement element) {
  std::vector<int> codes;
  for (int s = 0; s < layout.CoverageSamples(); ++s) codes.push_back(layout.Code(element, s));
  return codes;
}

std::vector<int> SampleList(raster::SampleMask mask) {
  std::vector<int> samples;
  for (int s = 0; mask >> s != 0; ++s) {
    if ((mask >> s) & 1u) samples.push_back(s);
  }
  return samples;
}

// --- JSON ---

nlohmann::ordered_json ColourJson(const fmask::Colour& c) { return {c.r, c.g, c.b, c.a}; }

// The clear colour's pseudo-primitive is null: it is not a triangle index.
nlohmann::ordered_json PrimitiveJson(std::uint32_t primitiveId) {
  return primitiveId == fmask::kClearPrimitive ? nlohmann::ordered_json(nullptr)
                                               : nlohmann::ordered_json(primitiveId);
}

nlohmann::ordered_json SlotsJson(const std::vector<fmask::FragmentSlot>& slots) {
  nlohmann::ordered_json json = nlohmann::ordered_json::array();
  for (const fmask::FragmentSlot& slot : slots) {
    json.push_back({{"occupied", slot.occupied},
                    {"primitive", PrimitiveJson(slot.primitiveId)},
                    {"colour", ColourJson(slot.colour)}});
  }
  return json;
}

nlohmann::ordered_json EventJson(const fmask::FmaskLayout& layout, const fmask::TraceEvent& e) {
  nlohmann::ordered_json causes = nlohmann::ordered_json::array();
  for (const fmask::UnknownCause cause : e.causesAfter) causes.push_back(CauseName(cause));
  return {{"pixel", {e.x, e.y}},
          {"primitive", e.primitiveId},
          {"colour", ColourJson(e.colour)},
          {"covered", SampleList(e.covered)},
          {"passed", SampleList(e.passed)},
          {"exact", SampleList(e.exact)},
          {"slots_before", SlotsJson(e.slotsBefore)},
          {"fmask_before", ElementHex(layout, e.fmaskBefore)},
          {"codes_before", Codes(layout, e.fmaskBefore)},
          {"victim", e.victim},
          {"slot", e.slot},
          {"slots_after", SlotsJson(e.slotsAfter)},
          {"fmask_after", ElementHex(layout, e.fmaskAfter)},
          {"codes_after", Codes(layout, e.fmaskAfter)},
          {"causes_after", causes},
          {"steps", e.steps}};
}

// --- Text ---

std::string FormatFloat(float value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", static_cast<double>(value));
  return text;
}

// Appended piecewise: GCC 12 flags `"literal" + std::string` with a false -Wrestrict.
std::string ColourText(const fmask::Colour& c) {
  std::string text = "(";
  text.append(FormatFloat(c.r)).append(", ").append(FormatFloat(c.g)).append(", ");
  text.append(FormatFloat(c.b)).append(", ").append(FormatFloat(c.a)).append(")");
  return text;
}

std::string PrimitiveText(std::uint32_t primitiveId) {
  return primitiveId == fmask::kClearPrimitive ? "clear" : std::to_string(primitiveId);
}

std::string SamplesText(raster::SampleMask mask) {
  std::string text;
  for (const int s : SampleList(mask)) text.append(text.empty() ? "" : ",").append(std::to_string(s));
  return text.empty() ? "-" : text;
}

// UNKNOWN shows as U; MSAA layouts (F == S) have no UNKNOWN code.
std::string CodesText(const fmask::FmaskLayout& layout, fmask::FmaskElement element) {
  std::string text;
  for (const int code : Codes(layout, element)) {
    text += text.empty() ? "" : " ";
    text += layout.IsEqaa() && code == layout.UnknownCode() ? "U" : std::to_string(code);
  }
  return text;
}

void AppendState(std::string& text, const char* label, const fmask::FmaskLayout& layout,
                 fmask::FmaskElement element, const std::vector<fmask::FragmentSlot>& slots) {
  text += "  ";
  text += label;
  text += " fmask " + ElementHex(layout, element) + "  codes " + CodesText(layout, element) + "\n";
  for (std::size_t i = 0; i < slots.size(); ++i) {
    text += "         slot " + std::to_string(i) + (slots[i].occupied ? " used" : " free") +
            "  primitive " + PrimitiveText(slots[i].primitiveId) + "  colour " +
            ColourText(slots[i].colour) + "\n";
  }
}

void AppendEvent(std::string& text, const fmask::FmaskLayout& layout, std::size_t index,
                 const fmask::TraceEvent& e) {
  text += "event " + std::to_string(index) + ": pixel (" + std::to_string(e.x) + ", " +
          std::to_string(e.y) + "), primitive " + std::to_string(e.primitiveId) + ", colour " +
          ColourText(e.colour) + "\n";
  text += "  samples covered " + SamplesText(e.covered) + "  passed " + SamplesText(e.passed) +
          "  exact " + SamplesText(e.exact) + "\n";
  AppendState(text, "before", layout, e.fmaskBefore, e.slotsBefore);
  text += "  victim " + (e.victim < 0 ? std::string("none") : std::to_string(e.victim)) +
          ", incoming slot " + (e.slot < 0 ? std::string("none") : std::to_string(e.slot)) + "\n";
  AppendState(text, "after ", layout, e.fmaskAfter, e.slotsAfter);
  text += "  causes";
  for (const fmask::UnknownCause cause : e.causesAfter) text += std::string(" ") + CauseName(cause);
  text += "\n";
  for (const std::string& step : e.steps) text += "  step   " + step + "\n";
}

}  // namespace

nlohmann::ordered_json TraceJson(const RasterCommandOptions& options,
                                 const fmask::EqaaSurface& surface) {
  const fmask::FmaskLayout& layout = surface.Layout();
  nlohmann::ordered_json traced = nlohmann::ordered_json::array();
  for (const fmask::TracedPixel& pixel : options.traced) traced.push_back({pixel.x, pixel.y});
  nlohmann::ordered_json events = nlohmann::ordered_json::array();
  for (const fmask::TraceEvent& event : surface.Trace()) events.push_back(EventJson(layout, event));
  return {{"schema", "aasim.raster.trace"},
          {"version", 1},
          {"eqaa", fmask::EqaaName(surface.Config())},
          {"policy", options.policy},
          {"init", options.fmaskInit},
          {"fmask_format", layout.FormatName()},
          {"bits_per_sample", layout.BitsPerSample()},
          {"unknown_code", layout.IsEqaa() ? nlohmann::ordered_json(layout.UnknownCode())
                                           : nlohmann::ordered_json(nullptr)},
          {"traced", traced},
          {"events", events}};
}

std::string TraceText(const RasterCommandOptions& options, const fmask::EqaaSurface& surface) {
  const fmask::FmaskLayout& layout = surface.Layout();
  const std::string unknown = layout.IsEqaa() ? "UNKNOWN shown as U" : "no UNKNOWN code";
  std::string text = "# aasim raster trace: " + fmask::EqaaName(surface.Config()) + ", policy " +
                     options.policy + ", FMASK init " + options.fmaskInit + ", " +
                     layout.FormatName() + " (" + std::to_string(layout.BitsPerSample()) +
                     " bits per sample, " + unknown + ")\n";
  if (surface.Trace().empty()) text += "# no colour-block update touched the traced pixels\n";
  for (std::size_t i = 0; i < surface.Trace().size(); ++i) {
    AppendEvent(text, layout, i, surface.Trace()[i]);
  }
  return text;
}

}  // namespace cli
