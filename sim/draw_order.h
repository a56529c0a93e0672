#pragma once
// The order in which the frame pipeline submits its triangles (sim::FrameSettings::drawOrder).
// Seed 001's CRAA notes list "Front to Back sorting" among the settings a correct coverage
// resolve needs: coverage samples carry no depth, so a fragment that later turns out to be hidden
// has already evicted or discarded what the samples knew (aa-facts §6). Sorting makes the nearest
// surface arrive first, so hidden fragments are rejected instead of accepted and then overwritten.
//
// Kept apart from sim/frame.h so plain configuration (study::ExperimentConfig, the command line)
// names an order without the machine's headers.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace sim {

enum class DrawOrder : std::uint8_t {
  Submission,           // the scene's triangle order (meshes in file order)
  FrontToBack,          // triangles by their nearest depth, stable
  ObjectsFrontToBack,   // objects (meshes) by their nearest triangle, stable; submission order inside
};

struct NamedDrawOrder {
  std::string_view name;
  DrawOrder order;
};
inline constexpr std::array<NamedDrawOrder, 3> kDrawOrders = {{
    {"submission", DrawOrder::Submission},
    {"front-to-back", DrawOrder::FrontToBack},
    {"objects-front-to-back", DrawOrder::ObjectsFrontToBack},
}};

constexpr std::string_view DrawOrderName(DrawOrder order) {
  for (const NamedDrawOrder& entry : kDrawOrders) {
    if (entry.order == order) return entry.name;
  }
  return "?";
}

constexpr std::optional<DrawOrder> DrawOrderByName(std::string_view name) {
  for (const NamedDrawOrder& entry : kDrawOrders) {
    if (entry.name == name) return entry.order;
  }
  return std::nullopt;
}

}  // namespace sim
