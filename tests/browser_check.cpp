// Headless Chromium check of an HTML report (see browser_check.h).

#include "browser_check.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <thread>

namespace cli::testing {

namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// file:// URL of an absolute path, percent-encoding everything but unreserved characters and '/'.
std::string FileUrl(const fs::path& absolute) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string url = "file://";
  for (const char c : absolute.string()) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte >= 'a' && byte <= 'z') || (byte >= 'A' && byte <= 'Z') || (byte >= '0' && byte <= '9') ||
        std::strchr("-._~/", c) != nullptr) {
      url += c;
    } else {
      url += '%';
      url += kHex[byte >> 4];
      url += kHex[byte & 15];
    }
  }
  return url;
}

std::string ShellQuoted(const std::vector<std::string>& args) {
  std::string line;
  for (const std::string& arg : args) {
    if (!line.empty()) line += ' ';
    if (arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_=/.:,") ==
        std::string::npos) {
      line += arg;
      continue;
    }
    line += '\'';
    for (const char c : arg) {
      if (c == '\'') {
        line += "'\\''";
      } else {
        line += c;
      }
    }
    line += '\'';
  }
  return line;
}

// Removes the scratch directory (Chromium profile, captured output) however the check ends.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "aasim-chromium-XXXXXX").string();
    if (::mkdtemp(pattern.data()) != nullptr) path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    if (!path_.empty()) fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Runs argv[0] with stdin from /dev/null and stdout/stderr into files, in its own process group so
// that a timeout (and any helper process left behind) is killed as a whole. Returns the wait
// status, or -1 with `error` set.
int Run(const std::vector<std::string>& args, const fs::path& outPath, const fs::path& errPath,
        std::chrono::seconds timeout, bool& timedOut, std::string& error) {
  timedOut = false;
  std::vector<char*> argv;
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const int in = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const int out = ::open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (in < 0 || out < 0 || err < 0) {
    error = std::string("cannot open capture files: ") + std::strerror(errno);
    for (const int fd : {in, out, err}) {
      if (fd >= 0) ::close(fd);
    }
    return -1;
  }
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    ::dup2(in, STDIN_FILENO);
    ::dup2(out, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    static constexpr char kFailed[] = "exec failed\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kFailed, sizeof kFailed - 1);
    ::_exit(127);
  }
  ::close(in);
  ::close(out);
  ::close(err);
  if (pid < 0) {
    error = std::string("fork failed: ") + std::strerror(errno);
    return -1;
  }
  ::setpgid(pid, pid);  // also from the parent, so the group exists before any kill below
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      error = std::string("waitpid failed: ") + std::strerror(errno);
      return -1;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      timedOut = true;
      ::kill(-pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(-pid, SIGKILL);  // renderer/GPU/zygote processes that outlived the browser, if any
  return status;
}

std::string DecodeEntities(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '&') {
      out += text[i];
      continue;
    }
    const std::size_t semicolon = text.find(';', i);
    if (semicolon == std::string::npos || semicolon - i > 10) {
      out += '&';
      continue;
    }
    const std::string name = text.substr(i + 1, semicolon - i - 1);
    if (name == "amp") {
      out += '&';
    } else if (name == "quot") {
      out += '"';
    } else if (name == "lt") {
      out += '<';
    } else if (name == "gt") {
      out += '>';
    } else if (name == "apos" || name == "#39") {
      out += '\'';
    } else if (name == "nbsp") {
      out += "\xC2\xA0";
    } else {
      out += '&';
      continue;
    }
    i = semicolon;
  }
  return out;
}

std::string LastLines(const std::string& text, int count) {
  std::size_t pos = text.size();
  while (count-- > 0 && pos > 0) {
    const std::size_t newline = text.rfind('\n', pos - 1);
    if (newline == std::string::npos) return text;
    pos = newline;
  }
  return text.substr(pos);
}

// Chromium's log lines start [pid:tid:MMDD/hhmmss.micros:LEVEL:FILE(:LINE|(LINE))]; console
// messages use the pseudo-file CONSOLE. Scanned by hand rather than with <regex>, whose GCC 12
// headers trip -Wmaybe-uninitialized in the sanitizer build.
bool SkipDigits(std::string_view text, std::size_t& at, std::size_t minimum, std::size_t exactly = 0) {
  const std::size_t start = at;
  while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at])) != 0) ++at;
  const std::size_t count = at - start;
  return count >= minimum && (exactly == 0 || count == exactly);
}

bool Expect(std::string_view text, std::size_t& at, char c) {
  if (at >= text.size() || text[at] != c) return false;
  ++at;
  return true;
}

bool IsLogLine(std::string_view line) {
  std::size_t at = 0;
  if (!Expect(line, at, '[') || !SkipDigits(line, at, 1) || !Expect(line, at, ':') || !SkipDigits(line, at, 1) ||
      !Expect(line, at, ':') || !SkipDigits(line, at, 4, 4) || !Expect(line, at, '/') ||
      !SkipDigits(line, at, 6, 6) || !Expect(line, at, '.') || !SkipDigits(line, at, 1) || !Expect(line, at, ':')) {
    return false;
  }
  const std::size_t level = at;
  while (at < line.size() && (std::isupper(static_cast<unsigned char>(line[at])) != 0 ||
                              std::isdigit(static_cast<unsigned char>(line[at])) != 0 || line[at] == '_')) {
    ++at;
  }
  return at > level && Expect(line, at, ':');
}

// The text after "[...:CONSOLE:N] " or "[...:CONSOLE(N)] ".
bool ConsoleText(std::string_view line, std::string& text) {
  const std::size_t close = line.find(']');
  if (line.empty() || line[0] != '[' || close == std::string_view::npos || close + 1 >= line.size() ||
      line[close + 1] != ' ') {
    return false;
  }
  const std::string_view prefix = line.substr(1, close - 1);
  if (prefix.find(' ') != std::string_view::npos) return false;
  const std::size_t console = prefix.rfind(":CONSOLE");
  if (console == std::string_view::npos) return false;
  std::size_t at = console + 8;
  const bool colonForm = Expect(prefix, at, ':') && SkipDigits(prefix, at, 1) && at == prefix.size();
  at = console + 8;
  const bool parenForm =
      Expect(prefix, at, '(') && SkipDigits(prefix, at, 1) && Expect(prefix, at, ')') && at == prefix.size();
  if (!colonForm && !parenForm) return false;
  text = std::string(line.substr(close + 2));
  return true;
}

// A console message ends with `", source: URL (LINE)`.
bool EndsConsoleMessage(std::string_view text) {
  if (text.find("\", source: ") == std::string_view::npos || text.empty() || text.back() != ')') return false;
  const std::size_t open = text.rfind(" (");
  if (open == std::string_view::npos) return false;
  std::size_t at = open + 2;
  return SkipDigits(text, at, 1) && at == text.size() - 1;
}

}  // namespace

// The value of attribute `name` in the dumped DOM's <body ...> start tag; false when absent.
bool BodyAttribute(const std::string& dom, const std::string& name, std::string& value) {
  std::size_t i = dom.find("<body");
  if (i == std::string::npos) return false;
  i += 5;
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; };
  while (i < dom.size()) {
    while (i < dom.size() && space(dom[i])) ++i;
    if (i >= dom.size() || dom[i] == '>' || dom[i] == '/') return false;
    const std::size_t nameStart = i;
    while (i < dom.size() && !space(dom[i]) && dom[i] != '=' && dom[i] != '>') ++i;
    const std::string attribute = dom.substr(nameStart, i - nameStart);
    std::string raw;
    if (i < dom.size() && dom[i] == '=') {
      ++i;
      if (i < dom.size() && (dom[i] == '"' || dom[i] == '\'')) {
        const char quote = dom[i++];
        const std::size_t end = dom.find(quote, i);
        if (end == std::string::npos) return false;
        raw = dom.substr(i, end - i);
        i = end + 1;
      } else {
        const std::size_t start = i;
        while (i < dom.size() && !space(dom[i]) && dom[i] != '>') ++i;
        raw = dom.substr(start, i - start);
      }
    }
    if (attribute == name) {
      value = DecodeEntities(raw);
      return true;
    }
  }
  return false;
}

std::vector<std::string> ConsoleMessagesInLog(const std::string& log) {
  std::vector<std::string> messages;
  std::string current;
  bool open = false;
  std::istringstream lines(log);
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (open && !IsLogLine(line)) {
      current += '\n';
      current += line;
      if (EndsConsoleMessage(line)) {
        messages.push_back(current);
        open = false;
      }
      continue;
    }
    if (open) {  // a new log line before the end marker: keep what we have
      messages.push_back(current);
      open = false;
    }
    if (ConsoleText(line, current)) {
      if (EndsConsoleMessage(current)) {
        messages.push_back(current);
      } else {
        open = true;
      }
    }
  }
  if (open) messages.push_back(current);
  return messages;
}

BrowserCheck CheckInChromium(const fs::path& html, std::chrono::seconds timeout) {
  BrowserCheck result;
  const char* configured = std::getenv("AASIM_CHROMIUM");
  const std::string chromium = configured != nullptr && *configured != '\0' ? configured : "/usr/bin/chromium";
  if (::access(chromium.c_str(), X_OK) != 0) {
    result.error = "no Chromium at " + chromium + ": run bash .ci/setup --tests to install chromium";
    return result;
  }
  std::error_code ec;
  const fs::path page = fs::absolute(html, ec);
  if (ec || !fs::is_regular_file(page)) {
    result.error = "no HTML file at " + html.string();
    return result;
  }
  const TempDir scratch;
  if (scratch.path().empty()) {
    result.error = std::string("cannot create a temporary directory: ") + std::strerror(errno);
    return result;
  }
  const std::vector<std::string> args{
      chromium,
      "--headless",
      "--no-sandbox",  // root in CI containers
      "--disable-gpu",
      "--disable-quic",
      "--no-first-run",
      "--disable-background-networking",
      "--disable-component-update",
      "--disable-sync",
      "--disable-extensions",
      "--host-resolver-rules=MAP * ~NOTFOUND",  // no DNS: Chromium still looks up update hosts
      "--user-data-dir=" + (scratch.path() / "profile").string(),
      "--enable-logging=stderr",
      "--v=0",
      "--virtual-time-budget=5000",  // let timers due within 5 s (virtual) run before the dump
      "--dump-dom",
      FileUrl(page)};
  result.commandLine = ShellQuoted(args);
  const fs::path outPath = scratch.path() / "dom.html", errPath = scratch.path() / "stderr.log";
  bool timedOut = false;
  const auto start = std::chrono::steady_clock::now();
  const int status = Run(args, outPath, errPath, timeout, timedOut, result.error);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (status == -1) return result;
  result.rawLog = ReadAll(errPath);
  const std::string dom = ReadAll(outPath);
  if (timedOut) {
    result.error = "Chromium did not finish within " + std::to_string(timeout.count()) + " s";
    return result;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    result.error = "Chromium failed (" +
                   (WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                      : "signal " + std::to_string(WTERMSIG(status))) +
                   "):" + LastLines(result.rawLog, 3);
    return result;
  }
  if (dom.find("<body") == std::string::npos) {
    result.error = "Chromium dumped no DOM:" + LastLines(result.rawLog, 3);
    return result;
  }
  result.ran = true;
  result.dom = dom;
  result.consoleErrors = ConsoleMessagesInLog(result.rawLog);
  std::string value;
  if (BodyAttribute(dom, "data-images", value)) {
    int loaded = 0, total = 0;
    char slash = 0;
    std::istringstream counts(value);
    if (counts >> loaded >> slash >> total && slash == '/') {
      result.imagesLoaded = loaded;
      result.imagesTotal = total;
    }
  }
  if (BodyAttribute(dom, "data-errors", value)) {
    std::istringstream failed(value);
    std::string entry;
    while (std::getline(failed, entry)) {
      if (!entry.empty()) result.loadErrors.push_back(entry);
    }
  }
  return result;
}

}  // namespace cli::testing
