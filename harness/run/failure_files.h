#pragma once
// A failed job's reason as one row of a table (summary.md, results.csv, the
// HTML report, the console's job line), and what a row cannot hold written
// beside the job's images in jobs/<job id>/, named by the reason:
//   failure.txt                         the whole message, when it has more
//                                       than one line or is longer than a row
//   shader-<program>-<stage>.glsl       each shader that failed to compile,
//                                       as compiled (the log's "0:" lines)
// Written whatever --no-images says: they are the failure's evidence.
#include <string>
#include <vector>

#include "gl/shader_failures.h"

namespace sb::run {

// Characters of a reason kept in the record before it points to failure.txt.
inline constexpr size_t kReasonRowChars = 400;

// The reason for `message`; writes the files it names. A file that cannot
// be written is said in the reason instead.
std::string failure_reason(const std::string& run_dir, const std::string& job_id,
                           const std::string& message,
                           const std::vector<gl::FailedShader>& shaders);

}  // namespace sb::run
