// All-or-nothing output sets (see output_dir.h).

#include "cli/output_dir.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>

#include "cli/output_error.h"

namespace cli {
namespace {

// Hidden and tagged with the process id, so concurrent runs into one directory do not collide
// and a crashed run's leftovers are recognisable.
std::filesystem::path TemporaryName(const std::filesystem::path& dir, std::string_view fileName) {
  std::string name(".");  // appended piecewise: GCC 12 flags "." + string with -Wrestrict
  name += fileName;
  name += ".aasim-tmp-";
  name += std::to_string(::getpid());
  return dir / name;
}

std::string Describe(const std::filesystem::path& path, const std::string& problem,
                     const std::string& osError) {
  return path.string() + ": " + problem + ": " + osError;
}

// Creating a file is the only reliable writability test (permissions, read-only mounts, quotas).
void ProbeWritable(const std::filesystem::path& dir) {
  const std::filesystem::path probe = TemporaryName(dir, "probe");
  std::FILE* file = std::fopen(probe.c_str(), "wb");
  if (file == nullptr) throw OutputError(Describe(dir, "cannot write", std::strerror(errno)));
  int osError = 0;
  if (std::fputc('\n', file) == EOF) osError = errno;
  // Buffered write errors (a full disk, a quota) only surface at close.
  if (std::fclose(file) != 0 && osError == 0) osError = errno;
  std::error_code ignored;
  std::filesystem::remove(probe, ignored);
  if (osError != 0) throw OutputError(Describe(dir, "cannot write", std::strerror(osError)));
}

}  // namespace

OutputDir::OutputDir(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw OutputError(Describe(dir_, "cannot create directory", error.message()));
  if (!std::filesystem::is_directory(dir_, error)) {
    throw OutputError(Describe(dir_, "cannot create directory", "not a directory"));
  }
  ProbeWritable(dir_);
}

OutputDir::~OutputDir() { RemoveTemporaries(); }

std::filesystem::path OutputDir::Stage(std::string_view fileName) {
  const std::filesystem::path final = dir_ / fileName;
  CreateFolders(final.parent_path());
  // Recorded before anything is written, so a writer that fails halfway is cleaned up too.
  staged_.push_back({TemporaryName(final.parent_path(), final.filename().string()), final});
  return staged_.back().temporary;
}

void OutputDir::CreateFolders(const std::filesystem::path& folder) {
  std::error_code error;
  if (folder == dir_ || std::filesystem::is_directory(folder, error)) return;
  CreateFolders(folder.parent_path());
  std::filesystem::create_directory(folder, error);
  if (error) throw OutputError(Describe(folder, "cannot create directory", error.message()));
  createdFolders_.push_back(folder);
}

std::vector<std::filesystem::path> OutputDir::Commit() {
  std::vector<std::filesystem::path> committed;
  for (const StagedFile& file : staged_) {
    std::error_code error;
    std::filesystem::rename(file.temporary, file.final, error);
    if (error) {
      // Built before RemoveTemporaries() clears staged_, which `file` points into.
      const OutputError failure(Describe(file.final, "cannot move into place", error.message()));
      for (const std::filesystem::path& done : committed) std::filesystem::remove(done, error);
      RemoveTemporaries();
      throw failure;
    }
    committed.push_back(file.final);
  }
  staged_.clear();
  createdFolders_.clear();
  return committed;
}

void OutputDir::RemoveTemporaries() noexcept {
  for (const StagedFile& file : staged_) {
    std::error_code ignored;
    std::filesystem::remove(file.temporary, ignored);
  }
  staged_.clear();
  // Newest first, so a folder is empty by the time it is removed; remove() leaves non-empty
  // folders (someone else's files) alone.
  for (auto folder = createdFolders_.rbegin(); folder != createdFolders_.rend(); ++folder) {
    std::error_code ignored;
    std::filesystem::remove(*folder, ignored);
  }
  createdFolders_.clear();
}

OutputDir OpenOutOption(const std::filesystem::path& out) {
  try {
    return OutputDir(out);
  } catch (const OutputError& error) {
    throw OutputError("--out " + std::string(error.what()));
  }
}

}  // namespace cli
