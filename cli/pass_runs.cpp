// A post pass under each strategy (see pass_runs.h).

#include "cli/pass_runs.h"

#include <stdexcept>
#include <string>

#include "cli/dispatch_output.h"

namespace cli {
namespace {

std::span<const study::DispatchRecord> Dispatches(std::span<const study::DispatchRecord> records, const PassRun& run) {
  return records.subspan(run.firstDispatch, run.endDispatch - run.firstDispatch);
}

}  // namespace

PassRuns RunUnderStrategies(sim::Machine& machine, const passes::PassConfig& pass, const passes::FrameInputs& frame,
                            std::span<const passes::Strategy> strategies, std::vector<study::DispatchRecord>& records) {
  PassRuns result;
  const std::string name(pass.Info().name);
  for (const passes::Strategy strategy : strategies) {
    // One instance per strategy, as the study makes them: a pass with history must not carry one
    // strategy's into the other's.
    const std::unique_ptr<passes::Pass> instance = pass.Make();
    PassRun run{.strategy = strategy, .output = {}, .firstDispatch = records.size()};
    run.output = instance->Run(machine, frame, strategy);
    study::TakeDispatches(machine, records, "", name, std::string(passes::StrategyName(strategy)));
    run.endDispatch = records.size();
    if (!result.runs.empty() && result.difference.Identical()) {
      result.difference = passes::CompareOutputs(result.runs.front().output, run.output);
    }
    result.runs.push_back(std::move(run));
  }
  return result;
}

double EstimatedMicroseconds(std::span<const study::DispatchRecord> records, const PassRun& run) {
  double total = 0.0;
  for (const study::DispatchRecord& record : Dispatches(records, run)) total += record.report.time.totalMicroseconds;
  return total;
}

void PrintStrategyComparison(std::ostream& out, std::span<const study::DispatchRecord> records,
                             const passes::PassInfo& info, const PassRuns& runs) {
  const PassRun& first = runs.runs.at(0);
  const PassRun& second = runs.runs.at(1);
  const std::string_view studied = info.studiedDispatches.front();
  out << "\n" << passes::StrategyName(first.strategy) << " vs " << passes::StrategyName(second.strategy) << ": "
      << studied << " (" << first.output.workItems << " work-set pixels)\n";
  PrintDispatchComparison(out, studied, passes::StrategyName(first.strategy), Dispatches(records, first),
                          passes::StrategyName(second.strategy), Dispatches(records, second));
  out << "identical output: "
      << (runs.difference.Identical() ? "yes (output and layers bit-identical)" : "NO, " + runs.difference.Describe())
      << '\n';
}

void ThrowIfStrategiesDiffer(const PassRuns& runs, const passes::PassInfo& info, const std::filesystem::path& outputs) {
  if (runs.difference.Identical()) return;
  throw std::runtime_error("--strategy both: the strategies' outputs differ (" + runs.difference.Describe() +
                           "): a bug in " + std::string(info.source) + " (outputs kept in " + outputs.string() + ")");
}

}  // namespace cli
