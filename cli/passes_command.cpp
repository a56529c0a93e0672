// `aasim passes` (see passes_command.h).

#include "cli/passes_command.h"

#include <cstdio>
#include <sstream>

#include <CLI/CLI.hpp>

#include "passes/registry.h"
#include "passes/resolve.h"

namespace cli {
namespace {

constexpr std::string_view kInputNames[] = {"colour", "depth", "normal", "object id", "velocity", "EQAA surface"};

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

template <typename Items, typename Name>
std::string Join(const Items& items, Name&& name) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : ", ") + std::string(name(item));
  return text;
}

void PrintPass(const passes::PassInfo& info, std::ostream& out) {
  out << info.name << ": " << info.description << " (" << info.source << ")\n"
      << "  strategies  " << Join(info.strategies, passes::StrategyName) << "\n"
      << "  studied     " << Join(info.studiedDispatches, [](std::string_view name) { return name; }) << "\n"
      << "  inputs      "
      << Join(info.inputs, [](passes::FrameInput input) { return kInputNames[static_cast<std::size_t>(input)]; })
      << (info.temporal ? "; keeps history across frames" : "") << "\n";
  if (!info.variantOf.empty()) out << "  variant of  " << info.variantOf << " (the report measures their difference)\n";
  for (const passes::SettingInfo& setting : info.settings) {
    out << "  " << setting.name << "=" << Number(setting.defaultValue) << "  " << passes::RangeText(setting)
        << (setting.integer && setting.allowed.empty() ? " integer" : "") << "  " << setting.doc << "\n";
  }
  for (const passes::Preset& preset : info.presets) {
    out << "  preset=" << preset.name << "  "
        << Join(preset.values, [](const auto& value) { return std::string(value.first) + "=" + Number(value.second); })
        << "\n";
  }
  if (info.settings.empty()) out << "  (no settings)\n";
}

// Resolves are not post passes (docs/passes.md "Resolves"), but a user choosing `aasim run
// --resolves` looks for them here too.
void PrintResolves(std::ostream& out) {
  out << "\nResolves of the EQAA surface (aasim run --resolves; docs/craa.md), besides the frame's box resolve:\n";
  for (const passes::RegisteredResolve& resolve : passes::AllResolves()) {
    const passes::ResolveInfo& info = resolve.info();
    out << info.name << ": " << info.description << " (" << info.source << ")\n"
        << "  reads       " << info.surfaces << "\n";
  }
}

}  // namespace

CLI::App* AddPassesCommand(CLI::App& app, PassesCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "passes",
      "List the registered post passes with their strategies, studied dispatches, inputs, settings and presets: "
      "what `--post NAME[:key=value,...]` of `aasim run` and `aasim frame` and `--pass`, `--preset` and `--set` of "
      "`aasim post` accept");
  command->add_option("names", options.names, "Passes to describe [default: all]")->type_name("NAME");
  return command;
}

void ResolvePassesOptions(const PassesCommandOptions& options) {
  for (const std::string& name : options.names) {
    try {
      passes::PassByName(name);
    } catch (const passes::SettingsError& error) {
      throw CLI::ValidationError(error.what());
    }
  }
}

void RunPassesCommand(const PassesCommandOptions& options, std::ostream& out) {
  const std::vector<std::string> names = options.names.empty() ? passes::PassNames() : options.names;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out << '\n';
    PrintPass(passes::PassByName(names[i]).info(), out);
  }
  if (options.names.empty()) PrintResolves(out);
}

std::string DescribeAllPasses() {
  std::ostringstream text;
  const std::vector<std::string> names = passes::PassNames();
  RunPassesCommand({.names = names}, text);
  return text.str();
}

}  // namespace cli
