#include "scenes/gltf_uri_sandbox.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <limits>
#include <vector>

#include "core/sha256.h"

namespace sb::gltf {
namespace {

namespace fs = std::filesystem;

// tinygltf decodes URIs this way (dlib::urldecode) before opening them, so the
// checks below look at exactly the name it will open.
std::string url_decode(const std::string& s) {
  const auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && i + 2 < s.size()) {
      // Invalid hex digits decode to garbage in tinygltf; refuse them instead.
      const int a = hex(s[i + 1]), b = hex(s[i + 2]);
      out += (a < 0 || b < 0) ? '\0' : static_cast<char>(a * 16 + b);
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

bool starts_with_ci(const std::string& s, const char* prefix) {
  const size_t n = std::strlen(prefix);
  if (s.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  return true;
}

// True when `p` (after resolving symbolic links) lies inside `dir` (canonical).
bool inside_folder(const fs::path& dir, const fs::path& p) {
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(p, ec);
  if (ec) return false;
  const fs::path rel = real.lexically_relative(dir);
  return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

// tinygltf reads buffers and images only through these, and only inside the
// glTF file's folder (it would also try the working directory, and expand
// '~' and environment variables, on its own); `user` is the sandbox's
// State: the folder, and the files read so far.
bool sandbox_exists(const std::string& path, void* user) {
  std::error_code ec;
  return inside_folder(static_cast<const UriSandbox::State*>(user)->dir, path) &&
         fs::is_regular_file(path, ec);
}

// Notes a file read (once, however many buffers or images name it).
void note_read(UriSandbox::State& state, const std::string& path,
               const std::vector<unsigned char>& bytes) {
  const fs::path relative = fs::path(path).lexically_normal().lexically_relative(state.dir);
  const std::string name = relative.empty() ? path : relative.generic_string();
  for (const core::InputFile& f : state.reads)
    if (f.name == name) return;
  state.reads.push_back({path, name,
                         core::sha256_hex(std::string_view(
                             reinterpret_cast<const char*>(bytes.data()), bytes.size()))});
}
std::string sandbox_expand(const std::string& path, void*) { return path; }
bool sandbox_read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                  void* user) {
  if (!sandbox_exists(path, user)) {
    if (err) *err = "outside the glTF file's folder or not a file";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (!in || ec || size > std::numeric_limits<uint32_t>::max()) {
    if (err) *err = "cannot read";
    return false;
  }
  out->resize(size);
  in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size));
  if (!in) {
    if (err) *err = "cannot read";
    return false;
  }
  note_read(*static_cast<UriSandbox::State*>(user), path, *out);
  return true;
}
bool sandbox_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is disabled";
  return false;
}

}  // namespace

UriSandbox::UriSandbox(const std::string& file) : ImportStep(file) {
  std::error_code ec;
  fs::path folder = fs::path(file).parent_path();
  if (folder.empty()) folder = ".";
  state_.dir = fs::weakly_canonical(fs::absolute(folder, ec), ec);
  if (ec) fail("", "cannot resolve the file's folder: " + ec.message());
}

void UriSandbox::check_uri(const json& value, const std::string& where) const {
  if (!value.is_string()) fail(where, "expected a string, found " + describe(value));
  const std::string uri = value.get<std::string>();
  if (starts_with_ci(uri, "data:")) return;  // embedded, decoded by tinygltf
  const size_t end = uri.find_first_of(":/?#");
  if (end != std::string::npos && end > 0 && uri[end] == ':')
    fail(where, quoted(uri.substr(0, end + 1)) +
                    " URIs are not allowed (only data: URIs and relative paths inside the "
                    "glTF file's folder): " +
                    quoted(uri));
  const std::string path = url_decode(uri);
  if (path.empty()) fail(where, "empty");
  if (path.find('\0') != std::string::npos) fail(where, "invalid %-escape in " + quoted(uri));
  if (path[0] == '/' || path[0] == '\\')
    fail(where,
         "absolute paths are not allowed (only paths relative to the glTF file): " + quoted(uri));
  size_t start = 0;
  while (start <= path.size()) {
    const size_t stop = std::min(path.find_first_of("/\\", start), path.size());
    if (path.compare(start, stop - start, "..") == 0 && stop - start == 2)
      fail(where,
           "'..' segments are not allowed (files must be inside the glTF file's "
           "folder): " +
               quoted(uri));
    start = stop + 1;
  }
  const fs::path full = dir() / path;
  std::error_code ec;
  if (!fs::exists(full, ec))
    fail(where, "file " + quoted(path) + " not found next to the glTF file");
  if (!inside_folder(dir(), full))
    fail(where, quoted(path) + " resolves outside the glTF file's folder (symbolic link)");
  if (!fs::is_regular_file(full, ec)) fail(where, quoted(path) + " is not a regular file");
}

tg::FsCallbacks UriSandbox::callbacks() {
  return {&sandbox_exists, &sandbox_expand, &sandbox_read, &sandbox_write, &state_};
}

}  // namespace sb::gltf
