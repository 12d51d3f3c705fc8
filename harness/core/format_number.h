#pragma once
// One number through a printf format ("%.4f", "%g"): the tables, the HTML
// report and `compare` all print numbers this way.
#include <string>

namespace sb::core {

std::string format_number(const char* printf_format, double v);

}  // namespace sb::core
