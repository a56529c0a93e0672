// The pass registry (see registry.h).

#include "passes/registry.h"

#include "passes/cmaa2/cmaa2.h"
#include "passes/copy/copy.h"
#include "passes/demo/demo.h"
#include "passes/filmic_smaa/filmic_smaa.h"
#include "passes/filmic_smaa/filmic_t2x.h"
#include "passes/fxaa/fxaa.h"
#include "passes/fxaa_miniengine/fxaa_miniengine.h"
#include "passes/hraa/hraa.h"
#include "passes/hraa/tfq.h"
#include "passes/mlaa/mlaa.h"
#include "passes/smaa/smaa.h"
#include "passes/smaa/smaa_1tx.h"
#include "passes/smaa/smaa_temporal.h"
#include "passes/taa_ue4/taa_ue4.h"
#include "passes/tscmaa/tscmaa.h"

namespace passes {

std::span<const RegisteredPass> AllPasses() {
  static const RegisteredPass kPasses[] = {
      {demo::Info, demo::Make},
      {copy::Info, copy::Make},
      {smaa::Info<smaa::Variant::Luma>, smaa::Make<smaa::Variant::Luma>},
      {smaa::Info<smaa::Variant::Colour>, smaa::Make<smaa::Variant::Colour>},
      {smaa::Info<smaa::Variant::Depth>, smaa::Make<smaa::Variant::Depth>},
      {smaa::Info<smaa::Variant::LumaPredicated>, smaa::Make<smaa::Variant::LumaPredicated>},
      {smaa::Info<smaa::Variant::S2x>, smaa::Make<smaa::Variant::S2x>},
      {smaa::T2xInfo, smaa::MakeT2x},
      {smaa::FourXInfo, smaa::MakeFourX},
      {smaa::OneTxInfo, smaa::MakeOneTx},
      {filmic_smaa::Info, filmic_smaa::Make},
      {filmic_smaa::FilmicT2xInfo, filmic_smaa::MakeFilmicT2x},
      {fxaa::Info, fxaa::Make},
      {fxaa_miniengine::Info, fxaa_miniengine::Make},
      {mlaa::Info<mlaa::Thresholding::Relative>, mlaa::Make<mlaa::Thresholding::Relative>},
      {mlaa::Info<mlaa::Thresholding::Absolute>, mlaa::Make<mlaa::Thresholding::Absolute>},
      {mlaa::Info<mlaa::Thresholding::Predicated>, mlaa::Make<mlaa::Thresholding::Predicated>},
      {cmaa2::Info, cmaa2::Make},
      {taa_ue4::Info, taa_ue4::Make},
      {tscmaa::Info, tscmaa::Make},
      {hraa::TfqInfo, hraa::MakeTfq},
      {hraa::HraaInfo, hraa::MakeHraa},
  };
  return kPasses;
}

std::vector<std::string> PassNames() {
  std::vector<std::string> names;
  for (const RegisteredPass& pass : AllPasses()) names.emplace_back(pass.info().name);
  return names;
}

const RegisteredPass& PassByName(std::string_view name) {
  for (const RegisteredPass& pass : AllPasses()) {
    if (pass.info().name == name) return pass;
  }
  std::string names;
  for (const std::string& each : PassNames()) names += (names.empty() ? "" : ", ") + each;
  throw SettingsError("unknown post pass '" + std::string(name) + "' (passes: " + names + ")");
}

PassConfig ResolvePass(std::string_view text) {
  const PassSpec spec = ParsePassSpec(text);
  const RegisteredPass& pass = PassByName(spec.name);
  return {&pass, ResolveSettings(spec, pass.info().settings, pass.info().presets)};
}

}  // namespace passes
