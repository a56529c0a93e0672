// The copy pass (see copy.h).

#include "passes/copy/copy.h"

#include "passes/work_set.h"

namespace passes::copy {
namespace {

constexpr std::string_view kMarkDispatch = "copy/mark";
constexpr std::string_view kCopyDispatch = "copy/copy";

constexpr WorkSetKernels kKernels{
    .detectDispatch = kMarkDispatch,
    .consumeDispatch = kCopyDispatch,
    .detectPixel = {.vgprs = 4, .sgprs = 8, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 4,
                    .source = "hand count: a constant stencil export"},
    .detectCompute = {.vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 8,
                      .source = "hand count: bounds compare, pack x | y << 16, append address"},
    .consume = {.vgprs = 8, .sgprs = 16, .ldsBytesPerGroup = 0, .valuInstructionsPerWave = 8,
                .source = "hand count: item unpack and address arithmetic around one load and one store"},
};

class CopyPass final : public Pass {
 public:
  const PassInfo& Info() const override { return copy::Info(); }

  PassOutput Run(sim::Machine& machine, const FrameInputs& frame, Strategy strategy) override {
    PassOutput output{.colour = {"copy/output", frame.Width(), frame.Height(), 4}, .layers = {}, .workItems = 0, .workSet = {}};
    auto makeMark = [](sim::Dispatch&, auto) { return [](const auto&, int, int) { return true; }; };
    auto makeCopy = [&](sim::Dispatch& d) {
      const sim::TextureView<glm::vec4> in = d.Read(*frame.colour);
      const sim::RwTextureView<glm::vec4> out = d.ReadWrite(output.colour);
      return [=](const auto& lane, int x, int y) { out.Store(lane, x, y, in.Load(lane, x, y)); };
    };
    output.SetWorkSet(workSet_.Run(machine, strategy, kKernels, frame.Width(), frame.Height(), makeMark, makeCopy));
    return output;
  }

 private:
  WorkSet workSet_{"copy"};
};

}  // namespace

const PassInfo& Info() {
  static const PassInfo info{
      .name = "copy",
      .description = "every pixel in the work set, copied: the strategies' cost when nothing is culled",
      .source = "passes/copy/copy.h",
      .settings = {},
      .presets = {},
      .inputs = {FrameInput::Colour},
      .studiedDispatches = {kCopyDispatch},
      .strategies = {Strategy::StencilCulled, Strategy::DeferredQueue},
      // Output colour, stencil byte, queue entry.
      .bytesPerPixel = sizeof(glm::vec4) + 1 + sizeof(std::uint32_t),
      .temporal = false,
  };
  return info;
}

std::unique_ptr<Pass> Make(const PassSettings&) { return std::make_unique<CopyPass>(); }

}  // namespace passes::copy
