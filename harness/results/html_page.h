#pragma once
// What every shadowbench HTML page shares: the style sheet, the script (sortable
// tables, and a check that every image loaded), and the escaping of text and
// of paths in URLs. Inline in each page, so that the pages work offline.
#include <string>

namespace sb::results {

// The style sheet, for a <style> element.
const char* page_style();

// The script, for a <script> element at the end of <body>:
//  - every table.sortable sorts by a header when it is clicked (or Enter):
//    numbers numerically, text with digits as numbers, empty cells last;
//  - after load, <body data-images-ok="true|false" data-missing="..."> says
//    which images did not load, each also logged with console.error, and the
//    element #image-status (hidden) shows them.
const char* page_script();

// & < > " ' as character references: safe in text and in quoted attributes.
std::string html_escape(const std::string& s);

// JSON text (nlohmann's dump) made safe as the content of a <script>
// element: '<', '>' and '&' as \u003c, \u003e and \u0026 (no "</script",
// "<!--" or "-->" can appear, so the HTML parser never leaves or enters the
// escaped states inside it), and U+2028 and U+2029 as \u2028 and \u2029 (line
// terminators to JavaScript before ES2019). The same JSON value to a parser.
std::string json_for_script(const std::string& json_text);

// A relative URL for a file path: every byte but unreserved characters and
// '/', '=', '+', ',' percent-encoded (':' too, so no segment reads as a scheme).
std::string url_path(const std::string& path);

}  // namespace sb::results
