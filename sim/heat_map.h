#pragma once
// Per-dispatch lane utilization per 8x8 screen tile: every launched lane that belongs to a pixel
// (a quad lane, a compute thread of a pixel grid, or a lane that attributed itself) is added to
// its tile by kind. Empty lanes of partial waves belong to no pixel and appear only in the
// dispatch counters. Increments are atomic adds, which commute: deterministic across threads.

#include <atomic>
#include <cstdint>
#include <vector>

#include "sim/wave.h"

namespace sim {

class TileHeatMap {
 public:
  TileHeatMap() = default;
  TileHeatMap(int width, int height);

  int Width() const { return width_; }    // pixels
  int Height() const { return height_; }
  int TilesX() const { return tilesX_; }
  int TilesY() const { return tilesY_; }
  bool Empty() const { return tilesX_ == 0; }

  void Add(int x, int y, LaneKind kind, std::uint32_t lanes = 1) {
    if (std::uint32_t* count = Count(x, y, kind)) {
      std::atomic_ref<std::uint32_t>(*count).fetch_add(lanes, std::memory_order_relaxed);
    }
  }
  // The tile (x, y) falls in, as one number; -1 off the map. Lanes of one tile can be added at
  // once (Add with a count): a compute group over a pixel grid is usually one 8x8 tile.
  long long TileOf(int x, int y) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return -1;
    return static_cast<long long>(Index(x / kTileSize, y / kTileSize));
  }
  // Add for a caller that alone adds to (x, y)'s tile during this dispatch: a pixel wave's bin
  // (32 px, whole 8x8 tiles) is one chunk on one host thread, so its lanes' tiles need no atomic
  // (ThreadSanitizer's every-pass test checks the claim).
  void AddOwned(int x, int y, LaneKind kind, std::uint32_t lanes = 1) {
    if (std::uint32_t* count = Count(x, y, kind)) *count += lanes;
  }

  std::uint32_t Active(int tx, int ty) const { return active_[Index(tx, ty)]; }
  std::uint32_t Helper(int tx, int ty) const { return helper_[Index(tx, ty)]; }
  std::uint32_t Dead(int tx, int ty) const { return dead_[Index(tx, ty)]; }
  std::uint32_t Launched(int tx, int ty) const { return Active(tx, ty) + Helper(tx, ty) + Dead(tx, ty); }
  // Active / launched lanes of the tile; negative when no lane of the tile was launched.
  float Utilization(int tx, int ty) const;

  friend bool operator==(const TileHeatMap&, const TileHeatMap&) = default;

 private:
  // The counter of (x, y)'s tile for lanes of `kind`; none off the map or for empty lanes.
  std::uint32_t* Count(int x, int y, LaneKind kind) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_ || kind == LaneKind::DeadEmpty) return nullptr;
    std::vector<std::uint32_t>& counts = kind == LaneKind::Active   ? active_
                                         : kind == LaneKind::Helper ? helper_
                                                                    : dead_;
    return &counts[Index(x / kTileSize, y / kTileSize)];
  }
  std::size_t Index(int tx, int ty) const {
    return static_cast<std::size_t>(ty) * static_cast<std::size_t>(tilesX_) + static_cast<std::size_t>(tx);
  }
  int width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0;
  std::vector<std::uint32_t> active_, helper_, dead_;
};

}  // namespace sim
