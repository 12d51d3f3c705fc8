#include "results/html_page.h"

#include <cstring>

namespace sb::results {

namespace {

constexpr const char* kPageStyle = R"css(
:root{--fg:#1d2330;--muted:#5d6677;--line:#d8dde6;--bg:#f5f6f8;--card:#fff}
*{box-sizing:border-box}
body{margin:0;font:14px/1.45 system-ui,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;color:var(--fg);background:var(--bg)}
header{background:#1d2330;color:#fff;padding:18px 28px 14px}
header h1{margin:0 0 6px;font-size:22px;font-weight:600}
header p{margin:2px 0;color:#c8d0de}
header a{color:#9dc2ff}
nav{margin-top:10px;font-size:13px}
nav a{margin-right:14px;white-space:nowrap}
main{padding:4px 28px 40px}
h2{font-size:19px;margin:26px 0 10px;padding-bottom:4px;border-bottom:2px solid var(--line)}
h3{font-size:15px;margin:22px 0 8px;font-weight:600}
h3 a{font-size:12px;font-weight:400;margin-left:8px}
.note{color:var(--muted);margin:4px 0 10px}
.banner{background:#fde5e5;color:#8c1414;border:1px solid #f0b4b4;padding:8px 12px;border-radius:6px;margin:14px 0 0}
.mono,.name{font-family:ui-monospace,"DejaVu Sans Mono",monospace;font-size:12.5px}
.table-wrap{overflow-x:auto}
table{border-collapse:collapse;background:var(--card);border:1px solid var(--line);font-size:12.5px}
th,td{padding:4px 7px;border-bottom:1px solid var(--line);text-align:left;white-space:nowrap}
th{background:#eaeef5;cursor:pointer;user-select:none}
th:hover{background:#dde4ef}
th[aria-sort=ascending]::after{content:" \25B2";font-size:9px}
th[aria-sort=descending]::after{content:" \25BC";font-size:9px}
td.num,th.num{text-align:right;font-variant-numeric:tabular-nums}
tbody tr:nth-child(even){background:#f9fafb}
tbody tr:hover{background:#eef3fb}
td.reason{white-space:normal;max-width:460px;color:var(--muted)}
dl.facts{margin:0;font-size:12px;display:grid;grid-template-columns:auto 1fr;gap:2px 10px;align-content:start}
dl.facts dt{color:var(--muted)}
dl.facts dd{margin:0;font-variant-numeric:tabular-nums;word-break:break-all}
.status{display:inline-block;padding:0 7px;border-radius:9px;font-size:12px;font-weight:600}
.s-ok{background:#e0f3e5;color:#16672d}
.s-skipped{background:#eaecf0;color:#566074}
.s-failed,.s-other{background:#fde3e3;color:#a01c1c}
.v-ok{background:#e0f3e5;color:#16672d}
.v-degraded{background:#fdf0d5;color:#8a5a00}
.v-broken,.v-failed{background:#fde3e3;color:#a01c1c}
.v-skipped{background:#eaecf0;color:#566074}
td.stab{white-space:normal;min-width:160px;vertical-align:top}
.charts{display:grid;grid-template-columns:repeat(auto-fill,minmax(520px,1fr));gap:16px}
.chart,.card{margin:0;background:var(--card);border:1px solid var(--line);border-radius:6px;padding:10px}
.chart img{width:100%;height:auto;display:block}
.chart figcaption{margin-top:6px;font-weight:600;font-size:13px}
.chart figcaption a{font-weight:400;font-size:12px;margin-left:8px}
.legend{display:flex;align-items:center;gap:12px;margin:4px 0 12px;flex-wrap:wrap}
.legend .bar{width:360px}
.legend .bar img{width:100%;height:14px;display:block;border:1px solid #9aa3b2}
.ticks{display:flex;justify-content:space-between;font-size:12px;color:var(--muted);font-variant-numeric:tabular-nums}
.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(480px,1fr));gap:14px;align-items:start}
.card.ref{border-color:#98b0dc;box-shadow:inset 3px 0 0 #5b82c9}
.card-head{display:flex;flex-wrap:wrap;align-items:baseline;gap:4px 10px;margin-bottom:8px}
.name{font-weight:600;word-break:break-all}
.nums{color:var(--muted);font-size:12px;font-variant-numeric:tabular-nums}
.pair{display:grid;grid-template-columns:1fr 1fr;gap:8px}
.pair img{width:100%;height:auto;display:block;background:#e9ebef}
.cap{font-size:12px;color:var(--muted);margin-top:2px}
.placeholder{display:flex;align-items:center;justify-content:center;aspect-ratio:4/3;background:#f1f2f5;border:1px dashed #c5cbd6;color:var(--muted);font-size:12px;text-align:center;padding:6px}
.reason-text{margin:8px 0 0;color:#7a2020;font-size:12.5px;white-space:pre-wrap;word-break:break-word}
.reason-text.s-skipped{color:var(--muted)}
img.missing{outline:3px solid #d22;min-height:40px}
)css";

constexpr const char* kPageScript = R"js(
(function () {
  'use strict';
  // Sorting: numbers (inf and -inf included) numerically, the rest as text
  // with digits compared as numbers; empty cells last in either direction.
  function key(cell) {
    var t = cell.textContent.trim();
    if (t === '') return null;
    if (t === 'inf') return Infinity;
    if (t === '-inf') return -Infinity;
    var n = Number(t);
    return isNaN(n) ? t : n;
  }
  function compare(a, b) {
    var an = typeof a === 'number', bn = typeof b === 'number';
    if (an && bn) return a < b ? -1 : a > b ? 1 : 0;
    if (an !== bn) return an ? -1 : 1;
    return a.localeCompare(b, undefined, {numeric: true});
  }
  document.querySelectorAll('table.sortable').forEach(function (table) {
    var heads = Array.prototype.slice.call(table.tHead.rows[0].cells);
    heads.forEach(function (th, col) {
      th.tabIndex = 0;
      th.title = 'Sort by ' + th.textContent;
      function sort() {
        var asc = th.getAttribute('aria-sort') !== 'ascending';
        heads.forEach(function (h) { h.removeAttribute('aria-sort'); });
        th.setAttribute('aria-sort', asc ? 'ascending' : 'descending');
        var body = table.tBodies[0];
        var rows = Array.prototype.map.call(body.rows, function (r, i) {
          return {row: r, i: i, k: key(r.cells[col])};
        });
        rows.sort(function (a, b) {
          if (a.k === null || b.k === null) {
            return (a.k === null) - (b.k === null) || a.i - b.i;
          }
          var c = compare(a.k, b.k);
          return (asc ? c : -c) || a.i - b.i;
        });
        rows.forEach(function (x) { body.appendChild(x.row); });
      }
      th.addEventListener('click', sort);
      th.addEventListener('keydown', function (e) {
        if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); sort(); }
      });
    });
  });
  // After every image has loaded or failed: record which did not load.
  window.addEventListener('load', function () {
    var missing = [];
    document.querySelectorAll('img').forEach(function (img) {
      if (img.complete && img.naturalWidth > 0) return;
      var src = img.getAttribute('src');
      missing.push(src);
      img.classList.add('missing');
      console.error('missing image: ' + src);
    });
    document.body.dataset.imagesOk = missing.length === 0 ? 'true' : 'false';
    document.body.dataset.missing = missing.join(' ');
    if (missing.length > 0) {
      var note = document.getElementById('image-status');
      note.textContent = missing.length + ' image(s) did not load: ' + missing.join(', ');
      note.hidden = false;
    }
  });
})();
)js";

}  // namespace

const char* page_style() { return kPageStyle; }

const char* page_script() { return kPageScript; }

std::string html_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string json_for_script(const std::string& json_text) {
  std::string out;
  out.reserve(json_text.size());
  for (size_t i = 0; i < json_text.size(); ++i) {
    const char c = json_text[i];
    // Outside strings JSON has none of these, so escaping them everywhere is
    // escaping them inside strings, where \uXXXX means the same character.
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '>') {
      out += "\\u003e";
    } else if (c == '&') {
      out += "\\u0026";
    } else if (c == '\xE2' && i + 2 < json_text.size() && json_text[i + 1] == '\x80' &&
               (json_text[i + 2] == '\xA8' || json_text[i + 2] == '\xA9')) {
      out += json_text[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

std::string url_path(const std::string& path) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char ch : path) {
    const unsigned char c = static_cast<unsigned char>(ch);
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       (c != 0 && std::strchr("-._~/=+,", c) != nullptr);
    if (plain) {
      out += ch;
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

}  // namespace sb::results
