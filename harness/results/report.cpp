#include "results/report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string_view>

#include "results/store.h"

namespace sb {
namespace {

using json = nlohmann::json;

// A number from a record ("nan"/"inf" strings included), or NaN if absent.
double number_at(const json& r, const json::json_pointer& p) {
  if (!r.contains(p)) return std::nan("");
  const json& v = r.at(p);
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const auto s = v.get<std::string>();
    if (s == "inf") return INFINITY;
    if (s == "-inf") return -INFINITY;
  }
  return std::nan("");
}

std::string fmt(double v, const char* spec) {
  if (std::isnan(v)) return "";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, v);
  return buf;
}

struct Column {
  const char* header;
  const char* pointer;
  const char* format;
};

const Column kColumns[] = {
    {"frame_ms", "/timing/frame/median_ms", "%.3f"},
    {"technique_ms", "/timing/technique/median_ms", "%.3f"},
    {"rmse", "/metrics/visibility/all/rmse", "%.5f"},
    {"mae", "/metrics/visibility/all/mae", "%.5f"},
    {"max_error", "/metrics/visibility/all/max_error", "%.4f"},
    {"psnr", "/metrics/visibility/all/psnr", "%.2f"},
    {"ssim", "/metrics/visibility/all/ssim", "%.4f"},
    {"frac_over_0.05", "/metrics/visibility/all/frac_over_0.05", "%.4f"},
    {"penumbra_rmse", "/metrics/visibility/penumbra/rmse", "%.5f"},
};

std::string csv_escape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string make_csv(const std::vector<json>& records) {
  std::string out = "scene,resolution,technique,status";
  for (const auto& c : kColumns) out += std::string(",") + c.header;
  out += ",reason\n";
  for (const auto& r : records) {
    out += csv_escape(r.value("scene_variant", "")) + "," + r.value("resolution", "") + "," +
           csv_escape(r.value("technique_variant", "")) + "," + r.value("status", "");
    for (const auto& c : kColumns)
      out += "," + fmt(number_at(r, json::json_pointer(c.pointer)), c.format);
    out += "," + csv_escape(r.value("reason", "")) + "\n";
  }
  return out;
}

namespace {

// Text from records (labels, reasons) inside a Markdown table or heading:
// the characters that end a cell, open code, links, emphasis or HTML are
// escaped and line breaks become spaces, so a label cannot break the table or
// inject markup. ('_' inside words is not emphasis in CommonMark.)
std::string md_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\n' || c == '\r' || c == '\t')
      out += ' ';
    else if (std::string_view("\\`*[]<>|").find(c) != std::string_view::npos)
      (out += '\\') += c;
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string make_markdown(const std::vector<json>& records, const std::string& title) {
  std::string out = "# " + md_text(title) + "\n\n";
  if (!records.empty()) {
    const json& r0 = records.front();
    out += "Backend `" + r0.value("backend", "") + "`, renderer `" + r0.value("gl_renderer", "") +
           "`, timing source `" + r0.value("timing_source", "") + "`. Error is measured on the " +
           "visibility buffer against the ray-traced reference (" +
           r0.value(json::json_pointer("/reference/method"), std::string("")) + ", " +
           std::to_string(r0.value(json::json_pointer("/reference/spp"), 0)) + " spp).\n";
  }
  std::map<std::string, std::vector<const json*>> groups;
  std::vector<std::string> order;
  for (const auto& r : records) {
    const std::string key = r.value("scene_variant", "") + " @ " + r.value("resolution", "");
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(&r);
  }
  for (const auto& key : order) {
    out += "\n## " + md_text(key) + "\n\n| technique | status |";
    for (const auto& c : kColumns) out += std::string(" ") + c.header + " |";
    out += "\n|---|---|";
    for (size_t i = 0; i < std::size(kColumns); ++i) out += "---:|";
    out += "\n";
    for (const json* r : groups[key]) {
      std::string status = r->value("status", "");
      if (status != "ok") status += ": " + r->value("reason", "");
      out += "| " + md_text(r->value("technique_variant", "")) + " | " + md_text(status) + " |";
      for (const auto& c : kColumns)
        out += " " + fmt(number_at(*r, json::json_pointer(c.pointer)), c.format) + " |";
      out += "\n";
    }
  }
  return out;
}

void write_reports(const std::string& run_dir, const std::vector<json>& records,
                   const std::string& title) {
  namespace fs = std::filesystem;
  write_file_atomically((fs::path(run_dir) / "results.csv").string(), make_csv(records));
  write_file_atomically((fs::path(run_dir) / "summary.md").string(), make_markdown(records, title));
}

}  // namespace sb
