#include "run/failure_files.h"

#include <filesystem>

#include "core/atomic_file.h"
#include "core/bounded_text.h"
#include "core/names.h"

namespace sb::run {

namespace fs = std::filesystem;

namespace {

// Writes `text` as <run_dir>/jobs/<id>/<file>; returns the file relative to
// the run folder, or why it could not be written.
std::string write_beside(const std::string& run_dir, const std::string& job_id,
                         const std::string& file, const std::string& text, bool& written) {
  const std::string rel = "jobs/" + job_id;
  try {
    core::make_own_folder(run_dir, rel);
    core::write_file_atomically((fs::path(run_dir) / rel / file).string(), text);
    written = true;
    return rel + "/" + file;
  } catch (const std::exception& ex) {
    written = false;
    return ex.what();
  }
}

}  // namespace

std::string failure_reason(const std::string& run_dir, const std::string& job_id,
                           const std::string& message,
                           const std::vector<gl::FailedShader>& shaders) {
  std::string reason = core::one_line_text(message, kReasonRowChars);
  // A compiler's log ends in a line break: that alone is still one line.
  const size_t end = message.find_last_not_of(" \t\r\n");
  const bool lines = end != std::string::npos && message.find_first_of("\r\n") < end;
  if (lines || reason != core::one_line_text(message)) {
    bool written = false;
    const std::string where = write_beside(
        run_dir, job_id, "failure.txt", message.back() == '\n' ? message : message + "\n", written);
    reason += written ? " (the whole message: " + where + ")"
                      : " (the whole message could not be written: " + where + ")";
  }
  for (const gl::FailedShader& s : shaders) {
    bool written = false;
    const std::string where = write_beside(
        run_dir, job_id, "shader-" + core::file_safe(s.program) + "-" + s.stage + ".glsl", s.source,
        written);
    reason += written ? "; assembled source of '" + s.program + "' (" + s.stage + "): " + where
                      : "; its shader's source could not be written: " + where;
  }
  return core::bounded_text(reason, core::kMessageChars);
}

}  // namespace sb::run
