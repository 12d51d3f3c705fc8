#pragma once
// The warnings a report puts above its tables when its records mix what
// their times must not be compared across: hosts (`merge
// --allow-mixed-hosts`, results/mixed_hosts.h) and sessions (a resumed run,
// results/sessions.h). Made once from the records, set by summary.md, the
// HTML report and the LaTeX export alike.
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

struct Banner {
  std::string title;  // "Mixed hosts"
  // What follows the title, a sentence ending before the list; text between
  // backticks is code (an option's name).
  std::string text;
  std::vector<std::string> items;  // plain text, one list item each
};

// The banners `records` call for, in this order: mixed hosts, mixed
// sessions. None for records of one host and one session.
std::vector<Banner> report_banners(const std::vector<record::JobRecord>& records);

// Each banner as bold title, text and a list: Markdown, HTML (a paragraph
// of class "banner warning" and a list) and LaTeX (a paragraph and an
// itemize), escaped for each.
std::string markdown_banners(const std::vector<Banner>& banners);
std::string html_banners(const std::vector<Banner>& banners);
std::string latex_banners(const std::vector<Banner>& banners);

}  // namespace sb::results
