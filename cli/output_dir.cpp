// All-or-nothing output sets (see output_dir.h).

#include "cli/output_dir.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>

#include <oneapi/tbb/task_group.h>

#include "cli/output_error.h"

namespace cli {
namespace {

namespace fs = std::filesystem;

// Every live OutputDir, for the signal thread. Its mutex also keeps a commit and the signal
// cleanup from interleaving. Never destroyed: a signal may arrive while statics are destroyed.
struct LiveDirs {
  std::mutex mutex;
  std::vector<OutputDir*> dirs;
};

LiveDirs& Live() {
  static LiveDirs* const live = new LiveDirs;
  return *live;
}

// Hidden and tagged with the process id, so concurrent runs into one directory do not collide
// and a crashed run's leftovers are recognisable: `tag` is "tmp" for new files (the staging
// folder, the probe), "old" for the previous files during a commit.
fs::path HiddenName(const fs::path& dir, std::string_view fileName, std::string_view tag) {
  std::string name(".");  // appended piecewise: GCC 12 flags "." + string with -Wrestrict
  name += fileName;
  name += ".aasim-";
  name += tag;
  name += '-';
  name += std::to_string(::getpid());
  return dir / name;
}

fs::path BackupName(const fs::path& final) {
  return HiddenName(final.parent_path(), final.filename().string(), "old");
}

std::string Describe(const fs::path& path, const std::string& problem, const std::string& osError) {
  return path.string() + ": " + problem + ": " + osError;
}

// Creating a file is the only reliable writability test (permissions, read-only mounts, quotas).
void ProbeWritable(const fs::path& dir) {
  const fs::path probe = HiddenName(dir, "probe", "tmp");
  std::FILE* file = std::fopen(probe.c_str(), "wb");
  if (file == nullptr) throw OutputError(Describe(dir, "cannot write", std::strerror(errno)));
  int osError = 0;
  if (std::fputc('\n', file) == EOF) osError = errno;
  // Buffered write errors (a full disk, a quota) only surface at close.
  if (std::fclose(file) != 0 && osError == 0) osError = errno;
  std::error_code ignored;
  fs::remove(probe, ignored);
  if (osError != 0) throw OutputError(Describe(dir, "cannot write", std::strerror(osError)));
}

// rename(2) replaces files but not directories; finding that out halfway through a set would
// cost a rollback, so it is checked before anything moves.
void RefuseDirectoryInTheWay(const fs::path& final) {
  std::error_code ignored;
  if (fs::is_directory(fs::symlink_status(final, ignored))) {
    throw OutputError(Describe(final, "cannot move into place", std::strerror(EISDIR)));
  }
}

void Move(const fs::path& from, const fs::path& to, const fs::path& named, const char* problem) {
  std::error_code error;
  fs::rename(from, to, error);
  if (error) throw OutputError(Describe(named, problem, error.message()));
}

// Returns whether there was a previous file to keep.
bool MoveAside(const fs::path& final) {
  std::error_code ignored;
  if (!fs::exists(fs::symlink_status(final, ignored))) return false;
  Move(final, BackupName(final), final, "cannot move the previous file aside");
  return true;
}

// `kept` as MoveOldFilesAside() returns it; restored in staging order, so the previous manifest
// is back only once its whole set is.
void PutBack(const std::vector<fs::path>& kept) noexcept {
  for (auto final = kept.rbegin(); final != kept.rend(); ++final) {
    std::error_code ignored;
    fs::rename(BackupName(*final), *final, ignored);
  }
}

// One staging folder per OutputDir of the process; the caller holds Live().mutex.
std::string StagingName() {
  static unsigned next = 0;
  return "staging" + std::to_string(next++);
}

// Writers open staged files by path, outside any lock, and create them (O_CREAT), so removing a
// staged file cannot stop a writer from creating it again a moment later. Renaming the folder
// first can: a file opened before the rename moves with the folder and is removed with it, an
// open after it finds no folder and fails. So nothing under `staging` survives this.
void RemoveStagingFolder(const fs::path& staging) noexcept {
  std::error_code error;
  if (!fs::exists(fs::symlink_status(staging, error))) return;
  fs::path gone = staging;
  gone += "-gone";
  fs::rename(staging, gone, error);
  const fs::path doomed = error ? staging : gone;  // not renamed: "-gone" is a reused pid's leftover
  fs::remove_all(doomed, error);
}

}  // namespace

OutputDir::OutputDir(fs::path dir) : dir_(std::move(dir)) {
  const std::lock_guard lock(Live().mutex);
  staging_ = HiddenName(dir_, StagingName(), "tmp");
  try {
    CreateFolders(dir_);
    std::error_code error;
    if (!fs::is_directory(dir_, error)) {
      throw OutputError(Describe(dir_, "cannot create directory", "not a directory"));
    }
    ProbeWritable(dir_);
  } catch (...) {
    RemoveTemporaries();
    throw;
  }
  Live().dirs.push_back(this);
}

struct OutputDir::Writers {
  tbb::task_group group;
};

void OutputDir::WriteLater(std::string_view fileName, std::function<void(const fs::path&)> write) {
  const fs::path temporary = Stage(fileName);
  if (!writers_) writers_ = std::make_unique<Writers>();
  writers_->group.run([temporary, write = std::move(write)] { write(temporary); });
}

void OutputDir::WaitForWriters() {
  if (writers_) writers_->group.wait();
}

OutputDir::~OutputDir() {
  // Staged files are removed only once no writer can still be creating one.
  try {
    WaitForWriters();
  } catch (...) {  // NOLINT(bugprone-empty-catch): the run is failing already; its files go below
  }
  const std::lock_guard lock(Live().mutex);
  RemoveTemporaries();
  std::erase(Live().dirs, this);
}

fs::path OutputDir::Stage(std::string_view fileName) {
  const std::lock_guard lock(Live().mutex);
  const fs::path final = dir_ / fileName;
  CreateFolders(final.parent_path());
  const fs::path temporary = staging_ / fileName;
  std::error_code error;
  fs::create_directories(temporary.parent_path(), error);
  if (error) throw OutputError(Describe(temporary.parent_path(), "cannot create directory", error.message()));
  // Recorded before anything is written, so a writer that fails halfway is cleaned up too.
  staged_.push_back({temporary, final});
  return temporary;
}

void OutputDir::CreateFolders(const fs::path& folder) {
  std::error_code error;
  if (folder.empty() || fs::is_directory(folder, error)) return;
  // A parent that exists but is no directory is left for mkdir to name ("Not a directory").
  if (!fs::exists(folder.parent_path(), error)) CreateFolders(folder.parent_path());
  fs::create_directory(folder, error);
  if (error) throw OutputError(Describe(folder, "cannot create directory", error.message()));
  createdFolders_.push_back(folder);
}

std::vector<fs::path> OutputDir::Commit(std::string_view manifest) {
  WaitForWriters();
  const std::lock_guard lock(Live().mutex);
  PutLast(manifest);
  std::vector<fs::path> kept;
  try {
    for (const StagedFile& file : staged_) RefuseDirectoryInTheWay(file.final);
    kept = MoveOldFilesAside();
    std::vector<fs::path> committed = MoveNewFilesIn();
    std::error_code ignored;
    for (const fs::path& final : kept) fs::remove(BackupName(final), ignored);
    staged_.clear();
    createdFolders_.clear();
    RemoveStagingFolder(staging_);
    return committed;
  } catch (const OutputError&) {
    PutBack(kept);
    RemoveTemporaries();
    throw;
  }
}

void OutputDir::PutLast(std::string_view manifest) {
  const fs::path last = dir_ / manifest;
  std::stable_partition(staged_.begin(), staged_.end(),
                        [&](const StagedFile& file) { return file.final != last; });
}

// Newest first: the previous manifest disappears before any file it lists, so a set caught
// halfway by a crash has no manifest. On failure the files already moved are put back.
std::vector<fs::path> OutputDir::MoveOldFilesAside() const {
  std::vector<fs::path> kept;
  try {
    for (auto file = staged_.rbegin(); file != staged_.rend(); ++file) {
      if (MoveAside(file->final)) kept.push_back(file->final);
    }
  } catch (const OutputError&) {
    PutBack(kept);
    throw;
  }
  return kept;
}

// In staging order, the manifest last. On failure the files already moved in are removed, to
// make room for the previous ones.
std::vector<fs::path> OutputDir::MoveNewFilesIn() const {
  std::vector<fs::path> committed;
  try {
    for (const StagedFile& file : staged_) {
      Move(file.temporary, file.final, file.final, "cannot move into place");
      committed.push_back(file.final);
    }
  } catch (const OutputError&) {
    std::error_code ignored;
    for (const fs::path& done : committed) fs::remove(done, ignored);
    throw;
  }
  return committed;
}

void OutputDir::RemoveTemporaries() noexcept {
  RemoveStagingFolder(staging_);
  staged_.clear();
  // Newest first, so a folder is empty by the time it is removed; remove() leaves non-empty
  // folders (someone else's files) alone.
  for (auto folder = createdFolders_.rbegin(); folder != createdFolders_.rend(); ++folder) {
    std::error_code ignored;
    fs::remove(*folder, ignored);
  }
  createdFolders_.clear();
}

void OutputDir::RemoveTemporariesOnSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  // SIGHUP too: a closed terminal or an ended ssh session is an interruption like any other.
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    // A shell starts background jobs with SIGINT ignored, nohup ignores SIGHUP: they must stay
    // immune to it.
    if (sigaction(signal, nullptr, &current) == 0 && current.sa_handler != SIG_IGN) sigaddset(&signals, signal);
  }
  // Blocked here, before any other thread exists, so every thread inherits the mask and the
  // signal can only reach the thread below, which runs ordinary (not async-signal) code.
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread([signals] {
    int signal = 0;
    while (sigwait(&signals, &signal) != 0) {
    }
    // Never released: nothing may be staged or committed between the cleanup and the end.
    Live().mutex.lock();
    for (OutputDir* dir : Live().dirs) dir->RemoveTemporaries();
    // Dying of the signal itself gives the caller the conventional status (128 + signal).
    pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
    ::raise(signal);
    // Reached only if a library installed its own handler; the mutex is held, so end here.
    std::_Exit(128 + signal);
  }).detach();
}

OutputDir OpenOutOption(const fs::path& out) {
  try {
    return OutputDir(out);
  } catch (const OutputError& error) {
    throw OutputError("--out " + std::string(error.what()));
  }
}

}  // namespace cli
