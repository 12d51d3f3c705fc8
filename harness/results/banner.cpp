#include "results/banner.h"

#include "results/html_page.h"
#include "results/latex_tables.h"
#include "results/mixed_hosts.h"
#include "results/report.h"
#include "results/sessions.h"

namespace sb::results {

using record::JobRecord;

namespace {

// `text` with its backtick-quoted parts set by `code` and the rest by `plain`.
template <class Plain, class Code>
std::string with_code(const std::string& text, Plain plain, Code code) {
  std::string out;
  bool in_code = false;
  size_t from = 0;
  for (;;) {
    const size_t tick = text.find('`', from);
    const std::string part = text.substr(from, tick == std::string::npos ? tick : tick - from);
    if (!part.empty()) out += in_code ? code(part) : plain(part);
    if (tick == std::string::npos) return out;
    in_code = !in_code;
    from = tick + 1;
  }
}

}  // namespace

std::vector<Banner> report_banners(const std::vector<JobRecord>& records) {
  std::vector<Banner> out;
  if (auto b = mixed_hosts_banner(records)) out.push_back(std::move(*b));
  if (auto b = Sessions(records).banner()) out.push_back(std::move(*b));
  return out;
}

std::string markdown_banners(const std::vector<Banner>& banners) {
  std::string out;
  for (const Banner& b : banners) {
    out += "\n**" + markdown_text(b.title) + ":** " +
           with_code(b.text, markdown_text, [](const std::string& c) { return "`" + c + "`"; }) +
           "\n\n";
    for (const std::string& item : b.items) out += "- " + markdown_text(item) + "\n";
    out += "\n";
  }
  return out;
}

std::string html_banners(const std::vector<Banner>& banners) {
  std::string out;
  for (const Banner& b : banners) {
    out += "<p class=\"banner warning\"><strong>" + html_escape(b.title) + ":</strong> " +
           with_code(b.text, html_escape,
                     [](const std::string& c) {
                       return "<span class=\"mono\">" + html_escape(c) + "</span>";
                     }) +
           "</p>\n<ul>\n";
    for (const std::string& item : b.items) out += "<li>" + html_escape(item) + "</li>\n";
    out += "</ul>\n";
  }
  return out;
}

std::string latex_banners(const std::vector<Banner>& banners) {
  std::string out;
  for (const Banner& b : banners) {
    out += "\n\\paragraph{" + latex_text(b.title) + ":} " +
           with_code(b.text, latex_text,
                     [](const std::string& c) { return "\\texttt{" + latex_text(c) + "}"; }) +
           "\n";
    if (b.items.empty()) continue;
    // An en dash, not itemize's bullet: the bullet is a TS1 glyph, which
    // pdflatex sets from a bitmap font (tried with TeX Live 2022).
    out += "\\begin{itemize}\n";
    for (const std::string& item : b.items) out += "\\item[--] " + latex_text(item) + "\n";
    out += "\\end{itemize}\n";
  }
  return out;
}

}  // namespace sb::results
