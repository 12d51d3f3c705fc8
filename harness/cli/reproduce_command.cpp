#include "cli/reproduce_command.h"

#include <array>
#include <cctype>
#include <fstream>
#include <iterator>
#include <string_view>

namespace sb::cli {

namespace {

// Options that decide which jobs run, or in which process: each takes a value.
constexpr std::array<std::string_view, 4> kDropped = {"--only", "--isolation", "--job-timeout",
                                                      "--take-turns"};

bool plain_word(const std::string& text) {
  if (text.empty()) return false;
  for (const char c : text)
    if (!(std::isalnum(static_cast<unsigned char>(c)) ||
          std::string_view("_-./=:,+@%").find(c) != std::string_view::npos))
      return false;
  return true;
}

}  // namespace

std::vector<std::string> own_arguments() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> out;
  size_t begin = 0;
  for (size_t nul = all.find('\0'); nul != std::string::npos; nul = all.find('\0', begin)) {
    out.push_back(all.substr(begin, nul - begin));
    begin = nul + 1;
  }
  return out;
}

std::string shell_word(const std::string& text) {
  if (plain_word(text)) return text;
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string reproduce_command(const std::vector<std::string>& arguments, const std::string& run_dir,
                              const std::string& job_id) {
  std::string out = "gdb --args";
  bool has_out = false;
  for (size_t i = 0; i < arguments.size(); ++i) {
    const std::string& a = arguments[i];
    bool dropped = false;
    for (const std::string_view option : kDropped) {
      if (a == option) {
        ++i;  // and its value
        dropped = true;
      } else if (a.rfind(std::string(option) + "=", 0) == 0) {
        dropped = true;
      }
    }
    if (dropped) continue;
    if (a == "--out" || a.rfind("--out=", 0) == 0) has_out = true;
    out += " " + shell_word(a);
  }
  if (!has_out) out += " --out " + shell_word(run_dir);
  // The id always quoted: it is a pattern of --only, and reads as one.
  return out + " --only '" + job_id + "' --isolation none";
}

}  // namespace sb::cli
