#pragma once
// Shared helpers for the command-line tests: a per-test scratch directory, running the built
// `aasim` binary with its stdout and stderr captured, and reading back the files it wrote
// (text, directory listings, EXR channels by name).

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

namespace cli::testing {

namespace fs = std::filesystem;

struct CommandResult {
  int exitCode = -1;
  std::string out;
  std::string err;
};

inline std::string ReadText(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

inline fs::path WriteFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Appended piecewise: GCC 12 flags `" " + string` with a false -Wrestrict.
inline void AppendQuoted(std::string& command, std::string_view prefix, const std::string& arg) {
  command += prefix;
  command += '\'';
  command += arg;
  command += '\'';
}

// Runs the built binary through the shell with stdout and stderr captured in `scratch`.
inline CommandResult RunAasim(const std::vector<std::string>& args, const fs::path& scratch) {
  std::string command;
  AppendQuoted(command, "", AASIM_BINARY);
  for (const std::string& arg : args) AppendQuoted(command, " ", arg);
  const fs::path outPath = scratch / "stdout.txt", errPath = scratch / "stderr.txt";
  AppendQuoted(command, " >", outPath.string());
  AppendQuoted(command, " 2>", errPath.string());
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadText(outPath);
  result.err = ReadText(errPath);
  return result;
}

// Starts the built binary without a shell (so the test can signal or wait4 it directly), stdout
// to `out` and stderr to `err` (the same path: both into one file). Returns its pid, -1 when it
// cannot start.
inline pid_t SpawnAasim(const std::vector<std::string>& args, const std::string& out, const std::string& err) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (err == out) {
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
  } else {
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  std::vector<std::string> strings{AASIM_BINARY};
  strings.insert(strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& arg : strings) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, AASIM_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

// The names in `dir`, sorted; empty when it does not exist.
inline std::vector<std::string> FilesIn(const fs::path& dir) {
  std::vector<std::string> names;
  if (!fs::exists(dir)) return names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

inline std::vector<std::string> ExrChannelNames(const fs::path& path) {
  Imf::InputFile file(path.c_str());
  std::vector<std::string> names;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    names.emplace_back(it.name());
  }
  return names;
}

// Every channel of an EXR file, by name.
inline std::map<std::string, std::vector<float>> ReadExrChannels(const fs::path& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  const std::size_t width = static_cast<std::size_t>(window.max.x - window.min.x + 1);
  const std::size_t height = static_cast<std::size_t>(window.max.y - window.min.y + 1);
  std::map<std::string, std::vector<float>> channels;
  Imf::FrameBuffer frameBuffer;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    std::vector<float>& values = channels[it.name()];
    values.resize(width * height);
    frameBuffer.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()),
                                             sizeof(float), sizeof(float) * width));
  }
  file.setFrameBuffer(frameBuffer);
  file.readPixels(window.min.y, window.max.y);
  return channels;
}

// A fresh, empty scratch directory per test (named after suite, test and process), removed
// afterwards.
class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    scratch_ = fs::temp_directory_path() / ("aasim_cli_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(scratch_);
    fs::create_directories(scratch_);
  }
  void TearDown() override { fs::remove_all(scratch_); }

  fs::path scratch_;
};

// A bad-input case of a subcommand: extra arguments after
// `COMMAND --width 64 --height 48 --out DIR` (they may write input files into the scratch dir),
// what stderr must name, why, and the exit code.
struct BadInput {
  std::string name;
  std::function<std::vector<std::string>(const fs::path& scratch)> args;
  std::string named;   // stderr must name the input...
  std::string reason;  // ...and say this about it, so it failed for the intended reason
  int exitCode;
};

// gtest names failing parameters by this instead of dumping the struct's bytes.
inline void PrintTo(const BadInput& input, std::ostream* os) { *os << input.name; }

// Runs the case and checks the refusal: its exit code and exactly one stderr line, prefixed
// "aasim COMMAND: " for usage errors (exit 2) and "aasim: " otherwise, naming the input and the
// reason. Returns the run so the caller can check what was (not) written to `out`.
inline CommandResult ExpectRefused(const std::string& command, const BadInput& input, const fs::path& scratch,
                                   const fs::path& out) {
  std::vector<std::string> args{command, "--width", "64", "--height", "48", "--out", out.string()};
  const std::vector<std::string> extra = input.args(scratch);
  args.insert(args.end(), extra.begin(), extra.end());
  const CommandResult run = RunAasim(args, scratch);
  EXPECT_EQ(run.exitCode, input.exitCode) << run.err;
  EXPECT_FALSE(run.err.empty());
  if (run.err.empty()) return run;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_EQ(run.err.back(), '\n');
  EXPECT_NE(run.err.find(input.named), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(input.reason), std::string::npos) << run.err;
  EXPECT_EQ(run.err.rfind(input.exitCode == 2 ? "aasim " + command + ": " : "aasim: ", 0), 0u) << run.err;
  return run;
}

}  // namespace cli::testing
