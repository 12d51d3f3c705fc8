#include "results/latex_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "core/error.h"
#include "core/format_number.h"
#include "results/control_baseline.h"
#include "results/noisy_jobs.h"

namespace sb::results {

using core::InputError;
using record::JobRecord;
using record::JobStatus;

namespace {

// The header of a column: its label (capitalised) and unit, "Frame (ms)".
std::string latex_header(const ReportColumn& c) {
  std::string label = c.label;
  if (!label.empty() && label[0] >= 'a' && label[0] <= 'z') label[0] = char(label[0] - 'a' + 'A');
  std::string out = latex_text(label);
  if (*c.unit != '\0') out += " (" + latex_text(c.unit) + ")";
  return out;
}

// Decimals that print `v` to `digits` significant digits.
int latex_decimals(double v, int digits) {
  if (v == 0.0) return 0;
  const int exponent = static_cast<int>(std::floor(std::log10(std::fabs(v))));
  return std::max(0, digits - 1 - exponent);
}

// `v` rounded as latex_number prints it (finite, at least 1e-4 in size, or 0).
double latex_rounded(double v, int digits) {
  if (!std::isfinite(v)) return v;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*e", std::max(0, digits - 1), v);
  return std::strtod(buf, nullptr);
}

// The value of `c` that is set in bold in `group`, compared as printed, or
// none (see latex_tables.h).
std::optional<double> latex_best(const std::vector<const JobRecord*>& group, const ReportColumn& c,
                                 int digits) {
  if (!c.numeric() || c.better == Better::Neither) return std::nullopt;
  const bool higher = c.better == Better::Higher;
  std::optional<double> best;
  int candidates = 0;
  for (const JobRecord* r : group) {
    if (r->status != JobStatus::Ok || is_control(group, *r)) continue;
    const std::optional<double> v = c.number(*r);
    if (!v || std::isnan(*v)) continue;
    ++candidates;
    if (!std::isfinite(*v) && !(higher && *v > 0)) continue;  // only +inf, and only up
    const double p = latex_rounded(*v, digits);
    if (!best || (higher ? p > *best : p < *best)) best = p;
  }
  if (candidates < 2) return std::nullopt;
  return best;
}

}  // namespace

const std::vector<std::string>& default_latex_columns() {
  static const std::vector<std::string> names = {"frame_ms",      "x_control", "rmse",
                                                 "penumbra_rmse", "ssim",      "flip"};
  return names;
}

std::vector<const ReportColumn*> latex_columns(const std::vector<std::string>& names,
                                               const std::vector<JobRecord>& records) {
  std::vector<const ReportColumn*> out;
  if (names.empty()) {
    for (const std::string& name : default_latex_columns()) {
      const ReportColumn& c = report_column(name);
      if (std::any_of(records.begin(), records.end(),
                      [&](const JobRecord& r) { return !c.cell(r).empty(); }))
        out.push_back(&c);
    }
    return out;
  }
  for (const std::string& name : names) {
    const auto& all = report_columns();
    const auto it = std::find_if(all.begin(), all.end(), [&](const ReportColumn& c) {
      return name == c.name && !c.per_group && name != "technique";
    });
    if (it == all.end()) {
      std::string valid;
      for (const ReportColumn& c : all)
        if (!c.per_group && std::string(c.name) != "technique")
          valid += (valid.empty() ? "" : ", ") + std::string(c.name);
      std::string problem = "unknown column \"" + name + "\": expected a comma-separated list of ";
      problem += valid;
      problem += " (the technique is always the first column)";
      throw InputError("", "--latex-columns", problem);
    }
    out.push_back(&*it);
  }
  return out;
}

namespace {

// The next code point of `s` at `at` (advanced past it); U+FFFD for a byte
// that does not start well-formed UTF-8 (overlong forms, surrogates and
// values above U+10FFFF included), which then takes one byte.
char32_t next_code_point(const std::string& s, size_t& at) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char b0 = byte(at);
  size_t len = 0;
  char32_t cp = 0, min = 0;
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    len = 2, cp = b0 & 0x1Fu, min = 0x80;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    len = 3, cp = b0 & 0x0Fu, min = 0x800;
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    len = 4, cp = b0 & 0x07u, min = 0x10000;
  }
  bool ok = len > 0 && at + len <= s.size();
  for (size_t i = 1; ok && i < len; ++i) {
    ok = (byte(at + i) & 0xC0u) == 0x80u;
    cp = (cp << 6) | (byte(at + i) & 0x3Fu);
  }
  if (!ok || cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
    ++at;
    return 0xFFFD;
  }
  at += len;
  return cp;
}

// The Latin letters (U+00C0 to U+017E) that LaTeX's own UTF-8 support sets
// in the default OT1 encoding with Computer Modern's Type 1 fonts (no extra
// package, no bitmap font): every letter of those two blocks but the ones
// OT1 lacks (Ð Þ ð þ, the ogonek and stroke letters Ą Đ Ę Į Ħ Ŧ Ų, Ŋ, Ŀ, ĸ,
// ŉ) and the signs × ÷. Tried one by one with pdflatex (TeX Live 2022).
bool latex_sets_itself(char32_t c) {
  if (c < 0xC0 || c > 0x17E) return false;
  switch (c) {
    case 0xD0:
    case 0xD7:
    case 0xDE:
    case 0xF0:
    case 0xF7:
    case 0xFE:
    case 0x104:
    case 0x105:
    case 0x110:
    case 0x111:
    case 0x118:
    case 0x119:
    case 0x126:
    case 0x127:
    case 0x12E:
    case 0x12F:
    case 0x138:
    case 0x13F:
    case 0x140:
    case 0x149:
    case 0x14A:
    case 0x14B:
    case 0x166:
    case 0x167:
    case 0x172:
    case 0x173:
      return false;
    default:
      return true;
  }
}

}  // namespace

std::string latex_text(const std::string& s) {
  std::string out;
  for (size_t at = 0; at < s.size();) {
    const char c = s[at];
    if (static_cast<unsigned char>(c) >= 0x80) {
      const size_t from = at;
      const char32_t cp = next_code_point(s, at);
      if (latex_sets_itself(cp)) {
        out.append(s, from, at - from);  // as UTF-8, LaTeX's input encoding
      } else {
        char code[16];
        std::snprintf(code, sizeof code, "U+%04X", static_cast<unsigned>(cp));
        out += "\\textless{}";
        out += code;
        out += "\\textgreater{}";
      }
      continue;
    }
    ++at;
    switch (c) {
      case '_':
        out += "\\_";
        break;
      case '&':
        out += "\\&";
        break;
      case '%':
        out += "\\%";
        break;
      case '#':
        out += "\\#";
        break;
      case '$':
        out += "\\ensuremath{\\$}";
        break;  // text \$ is a bitmap font below 10 pt
      case '{':
        out += "\\{";
        break;
      case '}':
        out += "\\}";
        break;
      case '~':
        out += "\\textasciitilde{}";
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      case '\\':
        out += "\\textbackslash{}";
        break;
      case '<':
        out += "\\textless{}";
        break;
      case '>':
        out += "\\textgreater{}";
        break;
      case '|':
        out += "\\textbar{}";
        break;
      case '\n':
      case '\r':
      case '\t':
        out += ' ';
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string latex_number(double v, int digits) {
  if (std::isnan(v)) return "--";
  if (std::isinf(v)) return v > 0 ? "$\\infty$" : "$-\\infty$";
  const std::string sign = v < 0 ? "$-$" : "";
  const double a = std::fabs(v);
  char buf[64];
  if (a != 0.0 && a < 1e-4) {
    std::snprintf(buf, sizeof buf, "%.*e", std::max(0, digits - 1), a);
    const std::string text = buf;
    const size_t e = text.find('e');
    return "$" + std::string(v < 0 ? "-" : "") + text.substr(0, e) + "\\times10^{" +
           std::to_string(std::stoi(text.substr(e + 1))) + "}$";
  }
  const double r = latex_rounded(a, digits);
  std::snprintf(buf, sizeof buf, "%.*f", latex_decimals(r, digits), r);
  return sign + buf;
}

std::string make_latex_table(const std::vector<const JobRecord*>& group,
                             const std::vector<const ReportColumn*>& columns, int digits) {
  std::string out;
  if (!group.empty()) {
    std::string name = group[0]->scene_variant + " @ " + group[0]->resolution;
    std::replace_if(
        name.begin(), name.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    out += "% shadowbench: " + name + "\n";
  }
  out += "% needs \\usepackage{booktabs}\n\\begin{tabular}{l";
  for (const ReportColumn* c : columns) out += c->numeric() ? "r" : "l";
  out += "}\n\\toprule\nTechnique";
  for (const ReportColumn* c : columns) out += " & " + latex_header(*c);
  out += " \\\\\n\\midrule\n";
  std::vector<std::optional<double>> best;
  best.reserve(columns.size());
  for (const ReportColumn* c : columns) best.push_back(latex_best(group, *c, digits));
  for (const JobRecord* r : group) {
    out += latex_text(r->technique_variant);
    if (is_control(group, *r)) out += " \\emph{(control)}";
    if (is_noisy(*r)) out += "\\textsuperscript{\\dag}";
    if (r->status != JobStatus::Ok && !columns.empty()) {
      out += " & \\multicolumn{" + std::to_string(columns.size()) + "}{l}{\\emph{" +
             latex_text(record::to_string(r->status)) + "}}";
    } else {
      for (size_t i = 0; i < columns.size(); ++i) {
        const ReportColumn& c = *columns[i];
        out += " & ";
        if (!c.numeric()) {
          out += latex_text(c.cell(*r));
          continue;
        }
        const double v = c.number(*r).value_or(std::nan(""));
        const std::string cell = latex_number(v, digits);
        if (best[i] && !std::isnan(v) && latex_rounded(v, digits) == *best[i])
          out += (cell.find('$') == std::string::npos ? "\\textbf{" : "\\textbf{\\boldmath") +
                 cell + "}";
        else
          out += cell;
      }
    }
    out += " \\\\\n";
  }
  out += "\\bottomrule\n";
  // The noisy rows' legend, under the rule (results/noisy_jobs.h).
  if (const auto over = noisy_thresholds(group)) {
    std::string range = core::format_number("%g", 100.0 * over->first);
    if (over->second != over->first)
      range += "--" + core::format_number("%g", 100.0 * over->second);
    out += "\\multicolumn{" + std::to_string(columns.size() + 1) +
           "}{l}{\\footnotesize\\dag{} noisy: the median's 95\\,\\% interval is wider than "
           "$\\pm$" +
           range + "\\,\\%} \\\\\n";
  }
  return out + "\\end{tabular}\n";
}

}  // namespace sb::results
