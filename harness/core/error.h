#pragma once
// Errors that reach the user, and the exit codes that tell them apart.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace sb::core {

enum ExitCode : int {
  kExitOk = 0,
  kExitJobsFailed = 1,  // the run finished but at least one job failed
  kExitBadInput = 2,    // a config, scene file or parameter is wrong
  kExitInternal = 3,    // an environment or internal problem (no GL context...)
};

// A place in a text file: 1-based line and column (in bytes); line 0 when
// unknown.
struct TextPosition {
  size_t line = 0;
  size_t column = 0;
  bool known() const { return line != 0; }
};

// Bad user input. The message names the file and the place in it (a JSON
// pointer, a glTF accessor, a technique parameter) so it can be fixed blind;
// with a position, as compilers and pbrt do: "file:LINE:COL (/pointer): what".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string where, const std::string& what, TextPosition at = {})
      : std::runtime_error(format(file, where, what, at)),
        file_(std::move(file)),
        where_(std::move(where)),
        problem_(what),
        position_(at) {}
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }
  const std::string& problem() const { return problem_; }  // the message without the place
  const TextPosition& position() const { return position_; }

 private:
  static std::string format(const std::string& file, const std::string& where,
                            const std::string& what, const TextPosition& at) {
    std::string m = file.empty() ? std::string("<input>") : file;
    if (at.known()) {
      // Appended piece by piece: GCC 12 warns (-Wstringop-overflow, a false
      // positive) on ":" + std::string when <string> comes from a precompiled
      // header, which loses the pragma libstdc++ silences it with.
      m += ':';
      m += std::to_string(at.line);
      m += ':';
      m += std::to_string(at.column);
      if (!where.empty()) {
        m += " (";
        m += where;
        m += ')';
      }
    } else if (!where.empty()) {
      m += ": at ";
      m += where;
    }
    m += ": ";
    m += what;
    return m;
  }
  std::string file_;
  std::string where_;
  std::string problem_;
  TextPosition position_;
};

// A GL, Embree or I/O failure while running one job: that job fails, the run goes on.
class JobError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace sb::core
