// The CRAA LUT resolve (see craa_lut_resolve.h).

#include "passes/craa/craa_lut_resolve.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include <unistd.h>

#include "passes/craa/craa_common.h"
#include "sim/eqaa_resolve.h"

namespace passes::craa {
namespace {

constexpr sim::KernelInfo kLutKernel{
    .vgprs = 24, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 48,
    .source = "hand count of the LUT resolve: four clamped neighbour addresses (8), the LUT index (3), four "
              "4-bit weight extracts (8), the own weight (4), five 4-channel multiply-adds and the 1/S scale "
              "(24), export (1 + the colour write)"};

bool MadeFor(const CraaLut& lut, const raster::SamplePattern& pattern) {
  if (lut.Samples() != pattern.Count()) return false;
  for (int table = 0; table < lut.Tables(); ++table) {
    for (int s = 0; s < pattern.Count(); ++s) {
      if (lut.Offsets(table)[static_cast<std::size_t>(s)] != pattern.Offset(table, s)) return false;
    }
  }
  return lut.Tables() == (pattern.SameInAllPixels() ? 1 : 4);
}

// FNV-1a of the pattern's JSON form and the fixture version: a stable name for its cached table.
std::string CacheName(const raster::SamplePattern& pattern, std::int64_t configurations) {
  std::uint64_t hash = 1469598103934665603ull;
  for (const char c : raster::FormatPatternJson(pattern) + "v" + std::to_string(kCraaLutVersion)) {
    hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  std::string count;
  if (configurations != 0) count.append("-").append(std::to_string(configurations));
  return "craa-lut-" + std::to_string(pattern.Count()) + "s-" + hex + count + ".json";
}

std::optional<CraaLut> ReadCached(const std::filesystem::path& file, const raster::SamplePattern& pattern) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  CraaLut lut = ParseCraaLut(text.str(), file.string());
  if (!MadeFor(lut, pattern)) return std::nullopt;
  return lut;
}

void WriteCached(const std::filesystem::path& file, const CraaLut& lut) {
  std::error_code error;
  std::filesystem::create_directories(file.parent_path(), error);
  const std::filesystem::path staged = file.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(staged, std::ios::binary | std::ios::trunc);
    out << FormatCraaLut(lut);
    if (!out.flush()) throw std::runtime_error(staged.string() + ": cannot write the CRAA LUT cache");
  }
  std::filesystem::rename(staged, file, error);
  if (error) {
    std::filesystem::remove(staged, error);
    throw std::runtime_error(file.string() + ": cannot write the CRAA LUT cache");
  }
}

template <typename Lane>
glm::vec4 LutPixel(const sim::EqaaView& eqaa, const sim::BufferView<std::uint16_t>& table, int samples, int tables,
                   const Lane& lane) {
  const glm::vec4 own = sim::ToVec4(eqaa.Fragment(lane, lane.x, lane.y, 0));
  const glm::vec4 up = Neighbour(eqaa, lane, Side::Up), bottom = Neighbour(eqaa, lane, Side::Bottom);
  const glm::vec4 left = Neighbour(eqaa, lane, Side::Left), right = Neighbour(eqaa, lane, Side::Right);
  const std::uint32_t fmask = static_cast<std::uint32_t>(eqaa.Fmask(lane, lane.x, lane.y)) & SampleBits(samples);
  const std::size_t index = (tables == 1 ? 0u : static_cast<std::size_t>(lane.quadPixel) << samples) | fmask;
  const LutEntry w = UnpackLutEntry(table.Load(lane, index));
  const auto weight = [](int count) { return static_cast<float>(count); };
  const glm::vec4 sum = own * weight(samples - w.Sum()) + up * weight(w.up) + bottom * weight(w.bottom) +
                        left * weight(w.left) + right * weight(w.right);
  return sum * (1.0f / static_cast<float>(samples));
}

class LutResolve final : public Resolve {
 public:
  LutResolve(const raster::SamplePattern& pattern, const CraaLut& lut)
      : pattern_(pattern), samples_(lut.Samples()), tables_(lut.Tables()),
        table_("resolve/craa-lut/table", lut.Entries().size(), sizeof(std::uint16_t)) {
    if (!MadeFor(lut, pattern)) {
      throw std::invalid_argument("craa-lut: the table was made for pattern " + lut.PatternName() +
                                  ", not for the frame's pattern " + pattern.Name());
    }
    for (std::size_t i = 0; i < lut.Entries().size(); ++i) table_.At(i) = PackLutEntry(lut.Entries()[i]);
  }
  const ResolveInfo& Info() const override { return LutInfo(); }

  sim::Texture2D<glm::vec4> Run(sim::Machine& machine, const fmask::EqaaSurface& surface) override {
    CheckSurface(LutInfo(), surface, pattern_);
    return RunResolveDispatch(machine, surface, "resolve/craa-lut", kLutKernel,
                              [&](sim::Dispatch& dispatch, const sim::EqaaView& eqaa) {
                                const sim::BufferView<std::uint16_t> table = dispatch.Read(table_);
                                return [this, eqaa, table](const sim::PixelLane& lane) {
                                  return LutPixel(eqaa, table, samples_, tables_, lane);
                                };
                              });
  }

 private:
  raster::SamplePattern pattern_;
  int samples_, tables_;
  sim::Buffer<std::uint16_t> table_;
};

}  // namespace

CraaLut CachedCraaLut(const raster::SamplePattern& pattern, const std::optional<std::filesystem::path>& cache,
                      std::int64_t configurations) {
  const LutGeneratorSettings settings = configurations == 0 ? LutGeneratorSettings{} : WithConfigurations({}, configurations);
  if (!cache) return GenerateCraaLut(pattern, settings);
  const std::filesystem::path file = *cache / CacheName(pattern, configurations);
  if (std::optional<CraaLut> cached = ReadCached(file, pattern)) return std::move(*cached);
  CraaLut lut = GenerateCraaLut(pattern, settings);
  WriteCached(file, lut);
  return lut;
}

const ResolveInfo& LutInfo() {
  static const ResolveInfo info{
      .name = "craa-lut",
      .description = "CRAA LUT resolve: per FMASK value, how many samples take the up, bottom, left and right "
                     "neighbours' fragments, from a table fitted to the sample pattern (seed 001)",
      .source = "passes/craa/craa_lut_resolve.h",
      .surfaces = "1F surfaces of 2 to 16 samples",
      .reads = ReadsCraaModes};
  return info;
}

std::unique_ptr<Resolve> MakeLut(const ResolveContext& context) {
  const raster::SamplePattern& pattern = RequirePattern(LutInfo(), context);
  return std::make_unique<LutResolve>(pattern, CachedCraaLut(pattern, context.tableCache, context.tableConfigurations));
}

std::unique_ptr<Resolve> MakeLutWith(const raster::SamplePattern& pattern, CraaLut lut) {
  return std::make_unique<LutResolve>(pattern, lut);
}

}  // namespace passes::craa
