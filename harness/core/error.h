#pragma once
// Errors that reach the user, and the exit codes that tell them apart.
#include <stdexcept>
#include <string>

namespace sb {

enum ExitCode : int {
  kExitOk = 0,
  kExitJobsFailed = 1,  // the run finished but at least one job failed
  kExitBadInput = 2,    // a config, scene file or parameter is wrong
  kExitInternal = 3,    // an environment or internal problem (no GL context...)
};

// Bad user input. The message names the file and the place in it (a JSON
// pointer, a glTF accessor, a technique parameter) so it can be fixed blind.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string where, const std::string& what)
      : std::runtime_error(format(file, where, what)),
        file_(std::move(file)),
        where_(std::move(where)) {}
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }

 private:
  static std::string format(const std::string& file, const std::string& where,
                            const std::string& what) {
    std::string m = file.empty() ? std::string("<input>") : file;
    if (!where.empty()) m += ": at " + where;
    return m + ": " + what;
  }
  std::string file_;
  std::string where_;
};

// A GL, Embree or I/O failure while running one job: that job fails, the run goes on.
class JobError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace sb
