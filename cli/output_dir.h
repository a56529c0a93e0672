#pragma once
// All-or-nothing output sets: every file of a run is written under a hidden temporary name in
// the output directory and renamed into place only when all of them were written, so a failed
// run never leaves a partial or corrupt set behind.

#include <filesystem>
#include <string_view>
#include <vector>

namespace cli {

class OutputDir {
 public:
  // Creates `dir` if needed and proves it writable with a probe file. Throws OutputError
  // ("DIR: problem: OS error") before any real work is done.
  explicit OutputDir(std::filesystem::path dir);
  // Removes every staged file that was not committed, so errors leave nothing behind.
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  const std::filesystem::path& Path() const { return dir_; }

  // The temporary path to write `fileName` to; it becomes Path() / fileName on Commit().
  // `fileName` may name a subfolder ("a/b.bin"): missing folders are created now and removed
  // again if the set is not committed.
  std::filesystem::path Stage(std::string_view fileName);

  // Renames every staged file into place and returns the final paths. If a rename fails, the
  // files already renamed are removed too (no partial set) and OutputError is thrown.
  std::vector<std::filesystem::path> Commit();

 private:
  struct StagedFile {
    std::filesystem::path temporary;
    std::filesystem::path final;
  };
  void CreateFolders(const std::filesystem::path& folder);
  void RemoveTemporaries() noexcept;

  std::filesystem::path dir_;
  std::vector<StagedFile> staged_;
  std::vector<std::filesystem::path> createdFolders_;  // in creation order
};

// An OutputDir for a command's --out option: OutputDir's errors, prefixed "--out " so the
// message names the option.
OutputDir OpenOutOption(const std::filesystem::path& out);

}  // namespace cli
