#include "config/json_file.h"

#include <sys/stat.h>

#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace sb {
namespace {

using json = nlohmann::json;

// Forwards every event to nlohmann's own DOM builder after checking depth and
// duplicate keys, and keeps the JSON pointer of where it is.
class CheckedSax {
 public:
  CheckedSax(json& root, const std::string& file, const std::string& text, const JsonLimits& limits,
             size_t line_offset)
      : dom_(root), file_(file), text_(text), limits_(limits), line_offset_(line_offset) {}

  bool null() { return value(dom_.null()); }
  bool boolean(bool v) { return value(dom_.boolean(v)); }
  bool number_integer(json::number_integer_t v) { return value(dom_.number_integer(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return value(dom_.number_unsigned(v)); }
  bool number_float(json::number_float_t v, const std::string& s) {
    return value(dom_.number_float(v, s));
  }
  bool string(std::string& v) { return value(dom_.string(v)); }
  bool binary(json::binary_t& v) { return value(dom_.binary(v)); }

  bool start_object(size_t n) {
    open(false);
    return dom_.start_object(n);
  }
  bool key(std::string& k) {
    Frame& f = frames_.back();
    f.key = k;
    f.key_read = true;
    if (!f.keys.insert(k).second)
      throw InputError(file_, pointer(), "the key \"" + k + "\" appears twice in this object");
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return value(dom_.end_object());
  }
  bool start_array(size_t n) {
    open(true);
    return dom_.start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return value(dom_.end_array());
  }

  template <typename Exception>
  bool parse_error(size_t position, const std::string& /*token*/, const Exception& ex) {
    std::string what = ex.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 2: syntax error ..."
    for (const char* start : {"syntax error", "number overflow"}) {
      const auto cut = what.find(start);
      if (cut != std::string::npos) {
        what = what.substr(cut);
        break;
      }
    }
    const std::string at = pointer();
    throw InputError(file_, location(position) + (at.empty() ? "" : " (" + at + ")"),
                     "invalid JSON: " + what);
  }

 private:
  struct Frame {
    bool array = false;
    size_t index = 0;
    std::string key;
    bool key_read = false;  // and its value not yet complete
    std::set<std::string> keys;
  };

  // A complete value was read: the enclosing array moves on.
  bool value(bool ok) {
    if (!frames_.empty()) {
      if (frames_.back().array)
        ++frames_.back().index;
      else
        frames_.back().key_read = false;  // between members: no key to name
    }
    return ok;
  }

  void open(bool array) {
    if (int(frames_.size()) >= limits_.max_depth)
      throw InputError(file_, pointer(),
                       "nested deeper than " + std::to_string(limits_.max_depth) + " levels");
    frames_.push_back({array, 0, {}, false, {}});
  }

  std::string pointer() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array) {
        p += "/" + std::to_string(f.index);
      } else if (f.key_read) {
        p += "/";
        for (char c : f.key) p += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
      }
    }
    return p;
  }

  std::string location(size_t byte) const {
    size_t line = 1, col = 1;
    for (size_t i = 0; i + 1 < byte && i < text_.size(); ++i) {
      if (text_[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    return "line " + std::to_string(line + line_offset_) + ", column " + std::to_string(col);
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  const std::string& file_;
  const std::string& text_;
  const JsonLimits& limits_;
  size_t line_offset_;
  std::vector<Frame> frames_;
};

}  // namespace

json parse_json_text(const std::string& text, const std::string& file, const JsonLimits& limits,
                     size_t line_offset) {
  if (text.size() > limits.max_bytes)
    throw InputError(file, "", "larger than " + std::to_string(limits.max_bytes) + " bytes");
  json root;
  CheckedSax sax(root, file, text, limits, line_offset);
  json::sax_parse(text, &sax);
  return root;
}

std::string read_input_file(const std::string& path, size_t max_bytes, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError(path, "", "cannot open the " + what);
  if (!S_ISREG(st.st_mode)) throw InputError(path, "", "the " + what + " is not a regular file");
  if (size_t(st.st_size) > max_bytes)
    throw InputError(path, "",
                     "the " + what + " is larger than " + std::to_string(max_bytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the " + what);
  std::string text;
  text.resize(size_t(st.st_size));
  in.read(text.data(), std::streamsize(text.size()));
  // The file may have changed size since stat: never read past the cap.
  text.resize(size_t(in.gcount()));
  if (in.peek() != std::char_traits<char>::eof())
    throw InputError(path, "", "the " + what + " grew while it was read");
  return text;
}

json read_json_file(const std::string& path, const JsonLimits& limits) {
  return parse_json_text(read_input_file(path, limits.max_bytes, "file"), path, limits);
}

}  // namespace sb
