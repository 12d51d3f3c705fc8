#include "config/json_file.h"

#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/json_reader.h"

namespace sb::config {

using core::InputError;
using core::JsonPositions;
using core::located;
using core::pointer_token;
using core::TextPosition;

namespace {

using json = nlohmann::json;

// The byte offset of the first '[' or '{' of `text` nested deeper than
// `depth` levels (text.size() if none): the value the depth cap refuses.
size_t first_deeper_than(const std::string& text, size_t depth) {
  size_t level = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++level > depth) return i;
    } else if ((c == ']' || c == '}') && level > 0) {
      --level;
    }
  }
  return text.size();
}

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
    throw InputError(file_, pointer(), "invalid JSON: " + what, location(position));
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
                       "nested deeper than " + std::to_string(limits_.max_depth) + " levels",
                       location(first_deeper_than(text_, size_t(limits_.max_depth)) + 1));
    frames_.push_back({array, 0, {}, false, {}});
  }

  std::string pointer() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array) {
        p += "/" + std::to_string(f.index);
      } else if (f.key_read) {
        p += "/" + pointer_token(f.key);
      }
    }
    return p;
  }

  TextPosition location(size_t byte) const {
    size_t line = 1, col = 1;
    for (size_t i = 0; i + 1 < byte && i < text_.size(); ++i) {
      if (text_[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    return {line + line_offset_, col};
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  const std::string& file_;
  const std::string& text_;
  const JsonLimits& limits_;
  size_t line_offset_;
  std::vector<Frame> frames_;
};

// Walks a text nlohmann has already accepted and records where each value
// starts. The grammar is JSON's own, so the walk is short; the nesting is
// already capped (JsonLimits::max_depth), so it may recurse.
class PositionScan {
 public:
  PositionScan(const std::string& text, JsonPositions& out) : t_(text), out_(out) {
    if (t_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = 3;  // a byte order mark, as nlohmann skips it
  }
  void value(const std::string& pointer) {
    space();
    out_.add(pointer, i_);
    if (t_[i_] == '{') {
      ++i_;
      space();
      while (t_[i_] != '}') {
        const size_t start = i_;
        skip_string();
        const auto key =
            json::parse(t_.begin() + std::ptrdiff_t(start), t_.begin() + std::ptrdiff_t(i_))
                .get<std::string>();
        space();
        ++i_;  // ':'
        value(pointer + "/" + pointer_token(key));
        space();
        if (t_[i_] == ',') ++i_;
        space();
      }
      ++i_;
    } else if (t_[i_] == '[') {
      ++i_;
      space();
      for (size_t n = 0; t_[i_] != ']'; ++n) {
        value(pointer + "/" + std::to_string(n));
        space();
        if (t_[i_] == ',') ++i_;
        space();
      }
      ++i_;
    } else if (t_[i_] == '"') {
      skip_string();
    } else {  // a number, true, false or null
      while (i_ < t_.size() && std::string_view(",]} \t\r\n").find(t_[i_]) == std::string::npos)
        ++i_;
    }
  }

 private:
  void space() {
    while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\t' || t_[i_] == '\n' || t_[i_] == '\r'))
      ++i_;
  }
  void skip_string() {
    for (++i_; t_[i_] != '"'; ++i_)
      if (t_[i_] == '\\') ++i_;
    ++i_;
  }
  const std::string& t_;
  JsonPositions& out_;
  size_t i_ = 0;
};

}  // namespace

json parse_json_text(const std::string& text, const std::string& file, const JsonLimits& limits,
                     size_t line_offset, JsonPositions* positions) {
  if (text.size() > limits.max_bytes)
    throw InputError(file, "", "larger than " + std::to_string(limits.max_bytes) + " bytes");
  json root;
  CheckedSax sax(root, file, text, limits, line_offset);
  try {
    json::sax_parse(text, &sax);
  } catch (const InputError& e) {
    // A key twice: the walk finds the second key's place (it keeps the last
    // of equal pointers), if the rest of the text is JSON and not too deep
    // for it: it trusts the grammar and recurses.
    if (e.position().known() || e.problem().find("appears twice") == std::string::npos ||
        !json::accept(text) || first_deeper_than(text, size_t(limits.max_depth)) < text.size())
      throw;
    JsonPositions where(text, line_offset);
    PositionScan(text, where).value("");
    throw located(e, file, where);
  }
  if (positions != nullptr) {
    *positions = JsonPositions(text, line_offset);
    PositionScan(text, *positions).value("");
  }
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

}  // namespace sb::config
