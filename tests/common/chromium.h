#pragma once
// Headless Chromium (Debian's chromium) on a page of the file system, for
// the tests of the HTML pages (the run report, the history site): the DOM
// after the page's script ran, or a screenshot, and the page's console.
//
// Chromium 156 prints every console message of the page to stderr (with
// --enable-logging=stderr) as `INFO:CONSOLE:<line>] "text", source: URL`,
// console.error and uncaught exceptions included, with no level of its own.
// The pages log nothing unless an image is missing, so any such line
// counts as an error.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "text.h"

namespace sb::test {

// `chromium` on PATH, else /usr/bin/chromium; empty when neither exists.
inline std::string find_chromium() {
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    for (std::string d; std::getline(dirs, d, ':');) {
      if (d.empty()) continue;
      const std::filesystem::path p = std::filesystem::path(d) / "chromium";
      if (::access(p.c_str(), X_OK) == 0) return p.string();
    }
  }
  return ::access("/usr/bin/chromium", X_OK) == 0 ? "/usr/bin/chromium" : "";
}

inline std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct BrowserRun {
  int exit_code = -1;
  std::string dom;                   // --dump-dom output (empty for a screenshot)
  std::vector<std::string> console;  // the page's console messages
  std::string log;                   // the whole of stderr, for failure messages
};

// One headless Chromium run on `page` with `mode` (--dump-dom or
// --screenshot=...). Everything that could reach a network is off, and host
// names resolve to nothing.
inline BrowserRun run_chromium(const std::string& chromium, const std::filesystem::path& work,
                               const std::filesystem::path& page, const std::string& mode) {
  const std::filesystem::path out = work / "chromium.out", err = work / "chromium.err";
  const std::string cmd =
      "timeout 120 " + shell_quote(chromium) +
      " --headless --no-sandbox --disable-gpu --no-first-run --no-default-browser-check"
      " --disable-extensions --disable-sync --disable-background-networking"
      " --disable-component-update --disable-default-apps --disable-domain-reliability"
      " --no-proxy-server --host-resolver-rules='MAP * ~NOTFOUND' --mute-audio"
      " --user-data-dir=" +
      shell_quote((work / "profile").string()) +
      " --enable-logging=stderr --v=0 --virtual-time-budget=5000 " + mode + " " +
      shell_quote("file://" + std::filesystem::absolute(page).string()) + " > " +
      shell_quote(out.string()) + " 2> " + shell_quote(err.string()) + " < /dev/null";
  BrowserRun r;
  const int status = std::system(cmd.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.dom = read_text(out);
  r.log = read_text(err);
  std::stringstream lines(r.log);
  for (std::string line; std::getline(lines, line);)
    if (line.find(":CONSOLE") != std::string::npos) r.console.push_back(line);
  return r;
}

inline std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

// A test that needs Chromium: skipped, saying what to install, where there is
// none (scripts/install-deps.sh --test installs it, so CI runs these).
class ChromiumTest : public ::testing::Test {
 protected:
  void SetUp() override {
    chromium_ = find_chromium();
    if (chromium_.empty())
      GTEST_SKIP() << "no Chromium (neither `chromium` on PATH nor /usr/bin/chromium): "
                      "install Debian's chromium package (scripts/install-deps.sh --test)";
  }
  std::string chromium_;
};

}  // namespace sb::test
