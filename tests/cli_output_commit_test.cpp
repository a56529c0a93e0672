// Output sets (docs/cli.md, "Output sets"): a failed commit leaves the previous set as it was,
// SIGTERM or SIGHUP at any moment of `run` and `fixtures` leaves the previous or the new complete
// set and no hidden file, even while a writer keeps creating its staged file, a failed `raster`
// leaves no directory, and a full stdout is an error.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cli/output_dir.h"
#include "cli/output_error.h"
#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;
using cli::testing::CommandResult;
using cli::testing::ReadText;
using cli::testing::RunAasim;
using cli::testing::WriteFile;
using Snapshot = std::map<std::string, std::string>;

class CliOutputCommit : public cli::testing::ScratchDirTest {};

// Every file and folder under `dir` by relative path (folders with a trailing '/'), with the
// files' bytes; hidden names included, so staging leftovers show.
Snapshot TakeSnapshot(const fs::path& dir) {
  Snapshot snapshot;
  if (!fs::exists(dir)) return snapshot;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(entry.path(), dir).string();
    if (entry.is_directory()) {
      snapshot[name + "/"] = "";
    } else {
      snapshot[name] = ReadText(entry.path());
    }
  }
  return snapshot;
}

std::vector<std::string> Names(const Snapshot& snapshot) {
  std::vector<std::string> names;
  for (const auto& [name, bytes] : snapshot) names.push_back(name);
  return names;
}

std::vector<std::string> RasterArgs(const fs::path& out, const std::string& width) {
  return {"raster", "--width", width, "--height", "32", "--samples", "8", "--fragments", "2", "--out", out.string()};
}

TEST_F(CliOutputCommit, ADirectoryInTheWayKeepsThePreviousSet) {
  const fs::path out = scratch_ / "out";
  ASSERT_EQ(RunAasim(RasterArgs(out, "64"), scratch_).exitCode, 0);
  const Snapshot previous = TakeSnapshot(out);
  fs::create_directory(out / "trace.json");
  std::vector<std::string> traced = RasterArgs(out, "48");
  traced.insert(traced.end(), {"--trace", "5,5"});
  const CommandResult run = RunAasim(traced, scratch_);
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(run.err, "aasim: " + (out / "trace.json").string() + ": cannot move into place: Is a directory\n");
  fs::remove(out / "trace.json");
  EXPECT_EQ(TakeSnapshot(out), previous);
}

// A rename that fails halfway (here: a staged file that was never written) puts back every
// previous file, the manifest included, and removes the folders the set created.
TEST_F(CliOutputCommit, AFailedRenameRestoresThePreviousSet) {
  const fs::path dir = scratch_ / "set";
  {
    cli::OutputDir out(dir);
    WriteFile(out.Stage("a.txt"), "old a");
    WriteFile(out.Stage("m.json"), "old m");
    out.Commit("m.json");
  }
  {
    cli::OutputDir out(dir);
    WriteFile(out.Stage("a.txt"), "new a");
    out.Stage("b/never-written.txt");
    WriteFile(out.Stage("m.json"), "new m");
    EXPECT_THROW(out.Commit("m.json"), cli::OutputError);
  }
  EXPECT_EQ(TakeSnapshot(dir), (Snapshot{{"a.txt", "old a"}, {"m.json", "old m"}}));
}

// Files written on worker threads (OutputDir::WriteLater) are all in place after Commit, even
// when their writers are still busy when Commit is called.
TEST_F(CliOutputCommit, FilesWrittenLaterAreCommittedWithTheSet) {
  cli::OutputDir out(scratch_ / "set");
  for (int i = 0; i < 8; ++i) {
    out.WriteLater("later/" + std::to_string(i) + ".txt", [i](const fs::path& path) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      WriteFile(path, "file " + std::to_string(i));
    });
  }
  WriteFile(out.Stage("m.json"), "m");
  out.Commit("m.json");
  Snapshot expected{{"later/", ""}, {"m.json", "m"}};
  for (int i = 0; i < 8; ++i) expected["later/" + std::to_string(i) + ".txt"] = "file " + std::to_string(i);
  EXPECT_EQ(TakeSnapshot(scratch_ / "set"), expected);
}

// A writer that fails on its worker thread fails the commit with its own error, and the previous
// set stays as it was with no staged file left behind.
TEST_F(CliOutputCommit, AWriterFailingLaterFailsTheCommitAndKeepsThePreviousSet) {
  const fs::path dir = scratch_ / "set";
  {
    cli::OutputDir out(dir);
    WriteFile(out.Stage("a.txt"), "old a");
    out.Commit();
  }
  {
    cli::OutputDir out(dir);
    WriteFile(out.Stage("a.txt"), "new a");
    out.WriteLater("b.txt", [](const fs::path& path) {
      WriteFile(path, "half");
      throw cli::OutputError(path.filename().string() + ": cannot write PNG");
    });
    try {
      out.Commit();
      ADD_FAILURE() << "the commit succeeded";
    } catch (const cli::OutputError& error) {
      EXPECT_STREQ(error.what(), "b.txt: cannot write PNG");
    }
  }
  EXPECT_EQ(TakeSnapshot(dir), (Snapshot{{"a.txt", "old a"}}));
}

// A set given up while a writer is still busy (an exception elsewhere) waits for it, then
// removes its file with the rest.
TEST_F(CliOutputCommit, ASetGivenUpWaitsForItsWritersThenLeavesNothing) {
  const fs::path dir = scratch_ / "fresh";
  {
    cli::OutputDir out(dir);
    out.WriteLater("slow.txt", [](const fs::path& path) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      WriteFile(path, "slow");
    });
  }
  EXPECT_FALSE(fs::exists(dir));
}

TEST_F(CliOutputCommit, TheManifestIsCommittedLast) {
  cli::OutputDir out(scratch_ / "set");
  WriteFile(out.Stage("m.json"), "m");
  WriteFile(out.Stage("a.txt"), "a");
  WriteFile(out.Stage("b.txt"), "b");
  const std::vector<fs::path> committed = out.Commit("m.json");
  EXPECT_EQ(committed, (std::vector<fs::path>{out.Path() / "a.txt", out.Path() / "b.txt", out.Path() / "m.json"}));
}

TEST_F(CliOutputCommit, ASceneErrorLeavesNoDirectory) {
  const fs::path fresh = scratch_ / "fresh" / "out";
  const fs::path existing = scratch_ / "existing";
  fs::create_directory(existing);
  for (const fs::path& out : {fresh, existing}) {
    const CommandResult run = RunAasim(
        {"raster", "--width", "16", "--height", "16", "--scene", "builtin:nosuch", "--out", out.string()}, scratch_);
    EXPECT_EQ(run.exitCode, 1) << run.err;
  }
  EXPECT_FALSE(fs::exists(scratch_ / "fresh"));
  EXPECT_TRUE(fs::is_empty(existing));
}

int ExitCodeWithFullStdout(const std::string& args, const fs::path& scratch) {
  const std::string command = std::string(AASIM_BINARY) + " " + args + " >/dev/full 2>'" +
                              (scratch / "stderr.txt").string() + "'";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(CliOutputCommit, AFullStdoutIsAnError) {
  const std::string out = (scratch_ / "out").string();
  for (const std::string& args : {std::string("--help"), "raster --width 16 --height 16 --out '" + out + "'"}) {
    EXPECT_EQ(ExitCodeWithFullStdout(args, scratch_), 1) << args;
    EXPECT_EQ(ReadText(scratch_ / "stderr.txt"), "aasim: standard output: write error\n") << args;
  }
}

// What the signal cleanup relies on: once a set is given up, a writer that opens its staged path
// only then (it got the path before) creates nothing.
TEST_F(CliOutputCommit, AStagedPathCannotBeCreatedOnceTheSetIsGivenUp) {
  const fs::path dir = scratch_ / "set";
  fs::create_directory(dir);
  fs::path staged;
  {
    cli::OutputDir out(dir);
    staged = out.Stage("late.bin");
  }
  std::ofstream(staged) << "x";
  EXPECT_EQ(Names(TakeSnapshot(dir)), std::vector<std::string>{});
}

// --- Signals ---

// The signals that would reach the process: one ignored here (nohup, a background job) stays
// ignored in the child, which would then never die of it.
std::vector<int> CatchableSignals() {
  std::vector<int> signals;
  for (const int signal : {SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (sigaction(signal, nullptr, &current) == 0 && current.sa_handler != SIG_IGN) signals.push_back(signal);
  }
  return signals;
}

// In a forked child: a set of many staged files (as `fixtures` has), the first of which a writer
// rewrites by path as fast as it can while the process signals itself, so the writer has the
// whole cleanup of the others to create the first one again.
[[noreturn]] void SignalWhileAWriterKeepsCreatingItsFile(const fs::path& dir, int signal) {
  cli::OutputDir::RemoveTemporariesOnSignals();
  cli::OutputDir out(dir);  // never destroyed: this never returns, only the signal cleans up
  const fs::path busy = out.Stage("busy.bin");
  for (int file = 0; file < 500; ++file) std::ofstream(out.Stage("done" + std::to_string(file))) << "x";
  std::thread([busy] {
    for (;;) std::ofstream(busy) << "x";
  }).detach();
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(::getpid(), signal);
  std::this_thread::sleep_for(std::chrono::seconds(20));  // the signal ends the process long before
  std::_Exit(0);
}

TEST_F(CliOutputCommit, ASignalLeavesNoStagedFileWhileAWriterKeepsCreatingIt) {
  for (const int signal : CatchableSignals()) {
    for (int round = 0; round < 4; ++round) {
      SCOPED_TRACE("signal " + std::to_string(signal) + ", round " + std::to_string(round));
      // An existing directory: one the run created would go with its files, taking the path from
      // under the writer.
      const fs::path dir = scratch_ / "set";
      fs::create_directory(dir);
      EXPECT_EXIT(SignalWhileAWriterKeepsCreatingItsFile(dir, signal), ::testing::KilledBySignal(signal), "");
      EXPECT_EQ(Names(TakeSnapshot(dir)), std::vector<std::string>{});
      fs::remove_all(dir);
    }
  }
}

// --- SIGTERM or SIGHUP at random moments ---

// Started directly (no shell in between to take the signal), output in `scratch`.
pid_t Spawn(const std::vector<std::string>& args, const fs::path& scratch) {
  const pid_t pid =
      cli::testing::SpawnAasim(args, (scratch / "stdout.txt").string(), (scratch / "stderr.txt").string());
  EXPECT_GT(pid, 0);
  return pid;
}

// The wait status of a run sent `signal` after `delay` (if still running by then).
int SignalAfter(const std::vector<std::string>& args, const fs::path& scratch, std::chrono::microseconds delay,
                int signal) {
  const pid_t pid = Spawn(args, scratch);
  if (pid <= 0) return -1;  // kill(-1) would signal every process of the user
  std::this_thread::sleep_for(delay);
  ::kill(pid, signal);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

std::chrono::microseconds TimedRun(const std::vector<std::string>& args, const fs::path& scratch) {
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  const pid_t pid = Spawn(args, scratch);
  if (pid > 0) ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << ReadText(scratch / "stderr.txt");
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start);
}

// After a good run into `out`, interrupts the same run at `points` random moments spread over
// its duration, every third time into a directory that does not exist yet, with the catchable
// signals in turn. Each time `out` must
// hold a complete set again (the same bytes when `deterministic`; `run`'s reports carry
// timings) and the new directory a complete set or nothing.
void ExpectOldOrNewSet(const std::vector<std::string>& command, bool deterministic, const fs::path& scratch,
                       int points) {
  const fs::path out = scratch / "out", fresh = scratch / "fresh";
  std::vector<std::string> args = command;
  args.insert(args.end(), {"--out", out.string()});
  const std::chrono::microseconds duration = TimedRun(args, scratch);
  const Snapshot good = TakeSnapshot(out);
  std::mt19937 random(10);
  std::uniform_int_distribution<std::int64_t> moment(0, duration.count() * 11 / 10);
  const std::vector<int> signals = CatchableSignals();
  ASSERT_FALSE(signals.empty());
  for (int point = 0; point < points; ++point) {
    const std::chrono::microseconds delay(moment(random));
    const bool intoFresh = point % 3 == 0;
    const fs::path dir = intoFresh ? fresh : out;
    const int signal = signals[static_cast<std::size_t>(point) % signals.size()];
    std::vector<std::string> interrupted = command;
    interrupted.insert(interrupted.end(), {"--out", dir.string()});
    const int status = SignalAfter(interrupted, scratch, delay, signal);
    SCOPED_TRACE("signal " + std::to_string(signal) + " after " + std::to_string(delay.count()) + " us into " +
                 dir.string());
    EXPECT_TRUE((WIFSIGNALED(status) && WTERMSIG(status) == signal) || (WIFEXITED(status) && WEXITSTATUS(status) == 0))
        << status << ": " << ReadText(scratch / "stderr.txt");
    if (intoFresh && !fs::exists(fresh)) continue;
    const Snapshot after = TakeSnapshot(dir);
    EXPECT_EQ(Names(after), Names(good));
    if (deterministic) {
      EXPECT_TRUE(after == good);
    }
    fs::remove_all(fresh);
  }
}

TEST_F(CliOutputCommit, SignalDuringRunLeavesTheOldOrTheNewSet) {
  // A frame of each kind (aliased, EQAA, 1F with the CRAA resolves) and two passes: the whole
  // output set's shape at a fraction of the default study's time (which is 8 modes and every pass).
  ExpectOldOrNewSet({"run", "--quick", "--width", "160", "--height", "96", "--modes", "1S/1Z/1F,8S/4Z/2F,8S/8Z/1F",
                     "--post", "demo,smaa", "--lut-configurations", "20000", "--cache", (scratch_ / "cache").string()},
                    false, scratch_, 8);
}

TEST_F(CliOutputCommit, SignalDuringFixturesLeavesTheOldOrTheNewSet) {
  ExpectOldOrNewSet({"fixtures"}, true, scratch_, 5);
}

}  // namespace
