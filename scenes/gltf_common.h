#pragma once
// What every step of the glTF import shares: how a problem is reported (the
// file, the place in it, what is wrong, as InputError), how places and
// values are named in those messages, and safe reads of tinygltf's loosely
// typed values (extras and extensions: tinygltf::Value asserts when read as
// the wrong kind, so each is checked before it is read).
#include <tiny_gltf.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace sb::gltf {

namespace tg = tinygltf;
using json = nlohmann::json;

// One step of importing one file: its errors name that file.
class ImportStep {
 public:
  explicit ImportStep(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }
  // Throws InputError(file, where, what).
  [[noreturn]] void fail(const std::string& where, const std::string& what) const;

 private:
  std::string file_;
};

std::string str(uint64_t v);
// 's', cut to 80 characters.
std::string quoted(const std::string& s);
// "node 'wheel' (5)" or "node 5".
std::string named(const std::string& kind, const std::string& name, size_t index);
// A JSON value's type and (cut) text: "string \"abc\"".
std::string describe(const json& v);
std::string first_line(const std::string& s);

// The member `key` of an object value, or nullptr.
const tg::Value* member(const tg::Value& v, const char* key);
// True, with the number in `out`, when `v` is a finite number.
bool finite_number(const tg::Value* v, double& out);

}  // namespace sb::gltf
