#pragma once
// Loads a self-contained HTML file in headless Chromium and reports what a reader's browser would
// show as broken: console output and uncaught exceptions (from Chromium's own log), elements whose
// resource failed to load and how many <img> decoded (from the body attributes data-errors and
// data-images="ok/total" that the report's inline script sets on 'load', read back from the DOM
// Chromium dumps). One Chromium run per call, bounded in time, against a file:// URL with host
// name resolution disabled, so no network is contacted.

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace cli::testing {

struct BrowserCheck {
  bool ran = false;    // Chromium ran to completion and dumped the DOM
  std::string error;   // why it did not (one line)
  // Every console message and uncaught exception of the page, as Chromium logs it:
  // `"text", source: URL (line)`. Chromium logs all console levels alike (log, warn, error), so a
  // report must stay silent: any message counts.
  std::vector<std::string> consoleErrors;
  std::vector<std::string> loadErrors;  // data-errors: one "tag alt-or-url" per failed resource
  int imagesLoaded = -1, imagesTotal = -1;  // data-images; -1 when the attribute is missing
  double seconds = 0.0;                      // wall time of the Chromium run
  std::string commandLine;                   // as run, shell-quoted
  std::string rawLog;                        // Chromium's stderr
  std::string dom;                           // the DOM Chromium dumped after the page ran
};

// Chromium is $AASIM_CHROMIUM when set, else /usr/bin/chromium.
BrowserCheck CheckInChromium(const std::filesystem::path& html,
                             std::chrono::seconds timeout = std::chrono::seconds(60));

// The value of attribute `name` in the dumped DOM's <body ...> start tag; false when absent.
bool BodyAttribute(const std::string& dom, const std::string& name, std::string& value);

// The page console messages in Chromium's stderr log: lines like
// `[pid:tid:MMDD/hhmmss.micros:INFO:CONSOLE:12] "text", source: URL (12)` (older builds write
// `CONSOLE(12)`), continued over following lines until `", source: URL (N)` for multi-line text.
// Chromium's other log lines (dbus, GPU, sandbox warnings) are ignored.
std::vector<std::string> ConsoleMessagesInLog(const std::string& log);

}  // namespace cli::testing
