#pragma once
// All-or-nothing output sets: every file of a run is written into a hidden staging folder in
// the output directory and renamed into place only when all of them were written, so a failed
// or interrupted run never leaves a partial or corrupt set behind and never loses the previous
// set (see docs/cli.md, "Output sets").

#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

namespace cli {

class OutputDir {
 public:
  // Creates `dir` if needed and proves it writable with a probe file. Throws OutputError
  // ("DIR: problem: OS error") before any real work is done. Folders it creates are removed
  // again if nothing is committed.
  explicit OutputDir(std::filesystem::path dir);
  // Removes every staged file and created folder that was not committed, so errors leave
  // nothing behind.
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  const std::filesystem::path& Path() const { return dir_; }

  // The temporary path to write `fileName` to; it becomes Path() / fileName on Commit().
  // `fileName` may name a subfolder ("a/b.bin"): missing folders are created now and removed
  // again if the set is not committed.
  std::filesystem::path Stage(std::string_view fileName);

  // Stages `fileName` now and runs write(the temporary path) on oneTBB's worker threads while the
  // caller goes on: for files whose encoding is slow and single-threaded (a 1080p PNG is about
  // 0.1 s of stb's deflate), so a run need not wait for each. Commit() first waits for every
  // such writer and throws the first failure; so does the destructor, which then cleans up.
  void WriteLater(std::string_view fileName, std::function<void(const std::filesystem::path&)> write);

  // Renames every staged file into place, `manifest` (a staged name, or empty) last, and
  // returns the final paths. Either the whole new set is in place afterwards, or OutputError is
  // thrown and the previous files are back as they were. Signals wait until it is done.
  std::vector<std::filesystem::path> Commit(std::string_view manifest = {});

  // Makes SIGINT, SIGTERM and SIGHUP remove every uncommitted staged file before the process
  // dies of the signal (exit status 128 + signal). Call first thing in main(), before any
  // thread starts: the signals are blocked in every thread and taken by one thread of its own.
  // A writer still creating a staged file meanwhile cannot leave it behind (output_dir.cpp,
  // RemoveStagingFolder).
  static void RemoveTemporariesOnSignals();

 private:
  struct StagedFile {
    std::filesystem::path temporary;
    std::filesystem::path final;
  };
  void CreateFolders(const std::filesystem::path& folder);
  void PutLast(std::string_view manifest);
  std::vector<std::filesystem::path> MoveOldFilesAside() const;
  std::vector<std::filesystem::path> MoveNewFilesIn() const;
  void RemoveTemporaries() noexcept;
  void WaitForWriters();

  struct Writers;  // oneTBB's task group, kept out of this header

  std::filesystem::path dir_;
  std::filesystem::path staging_;  // hidden, in dir_; every temporary lives under it
  std::vector<StagedFile> staged_;
  std::vector<std::filesystem::path> createdFolders_;  // in creation order
  std::unique_ptr<Writers> writers_;
};

// An OutputDir for a command's --out option: OutputDir's errors, prefixed "--out " so the
// message names the option.
OutputDir OpenOutOption(const std::filesystem::path& out);

}  // namespace cli
