// Pass settings: the "name:key=value" grammar, presets, and every way a value can be refused.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "passes/registry.h"
#include "passes/settings.h"

namespace passes {
namespace {

const SettingInfo kSchema[] = {
    {.name = "threshold", .defaultValue = 0.1, .min = 0.0, .max = 0.5, .minExclusive = true, .doc = "t"},
    {.name = "steps", .defaultValue = 8, .min = 0, .max = 112, .integer = true, .doc = "s"},
};
const Preset kPresets[] = {
    {"low", {{"threshold", 0.15}, {"steps", 4}}},
    {"ultra", {{"threshold", 0.05}, {"steps", 32}}},
};

PassSettings Resolve(const std::string& text) { return ResolveSettings(ParsePassSpec(text), kSchema, kPresets); }

std::string ErrorOf(const std::string& text) {
  try {
    Resolve(text);
  } catch (const SettingsError& error) {
    return error.what();
  }
  return "no error";
}

TEST(PassesSettings, DefaultsPresetsAndOverridesApplyInThatOrder) {
  EXPECT_EQ(Resolve("x").Get("threshold"), 0.1);
  EXPECT_EQ(Resolve("x:preset=low").Get("steps"), 4);
  // An explicit value wins over the preset wherever the preset is named.
  EXPECT_EQ(Resolve("x:steps=16,preset=ultra").Get("steps"), 16);
  EXPECT_EQ(Resolve("x:steps=16,preset=ultra").Get("threshold"), 0.05);
  EXPECT_EQ(Resolve("x:threshold=5e-1").Get("threshold"), 0.5);
  EXPECT_EQ(DescribeSettings(Resolve("x:preset=low")), "threshold=0.15, steps=4");
}

TEST(PassesSettings, RefusesWhatItCannotApplyNamingPassAndKey) {
  EXPECT_EQ(ErrorOf("x:threshold=0"), "pass x: threshold=0 outside (0, 0.5]");
  EXPECT_EQ(ErrorOf("x:threshold=0.6"), "pass x: threshold=0.6 outside (0, 0.5]");
  EXPECT_EQ(ErrorOf("x:steps=2.5"), "pass x: steps=2.5 must be an integer");
  EXPECT_EQ(ErrorOf("x:steps=-1"), "pass x: steps=-1 outside [0, 112]");
  EXPECT_EQ(ErrorOf("x:speed=1"), "pass x: unknown setting 'speed' (settings: threshold, steps)");
  EXPECT_EQ(ErrorOf("x:preset=medium"), "pass x: unknown preset 'medium' (presets: low, ultra)");
  for (const char* bad : {"x:threshold=nan", "x:threshold=inf", "x:threshold=0x1", "x:threshold=", "x:threshold=0.1 ",
                          "x:threshold=1e400"}) {
    EXPECT_NE(ErrorOf(bad).find("is not a finite decimal number"), std::string::npos) << bad;
  }
  EXPECT_EQ(ErrorOf("x:threshold"), "pass x: 'threshold' is not key=value");
  EXPECT_EQ(ErrorOf("x:steps=1,steps=2"), "pass x: steps is given twice");
  EXPECT_EQ(ErrorOf(":steps=1"), "pass spec ':steps=1': no pass name before ':'");
}

TEST(PassesSettings, APassListSplitsBetweenPassesNotBetweenSettings) {
  EXPECT_EQ(SplitPassList("demo"), std::vector<std::string>{"demo"});
  EXPECT_EQ(SplitPassList("demo:threshold=0.2,smaa:preset=high,threshold=0.05,copy"),
            (std::vector<std::string>{"demo:threshold=0.2", "smaa:preset=high,threshold=0.05", "copy"}));
  EXPECT_EQ(SplitPassList("demo,threshold=0.2"), std::vector<std::string>{"demo:threshold=0.2"});
  EXPECT_THROW(SplitPassList("threshold=0.2,demo"), SettingsError);
  EXPECT_THROW(SplitPassList("demo,,smaa"), SettingsError);
  EXPECT_THROW(SplitPassList(""), SettingsError);
}

TEST(PassesSettings, TheRegistryResolvesNamesAndRefusesUnknownOnes) {
  EXPECT_EQ(ResolvePass("demo").Info().name, "demo");
  try {
    ResolvePass("nosuch:threshold=1");
    FAIL();
  } catch (const SettingsError& error) {
    EXPECT_NE(std::string(error.what()).find("unknown post pass 'nosuch' (passes: demo"), std::string::npos)
        << error.what();
  }
  // Names are unique: the registry is a list a user selects from by name.
  std::vector<std::string> names = PassNames();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
}

}  // namespace
}  // namespace passes
