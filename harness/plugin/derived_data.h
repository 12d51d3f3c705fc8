#pragma once
// The data the plan derived for one scene, by need name (plugin/needs.h).
// Values are shared and immutable; a need without data (a pure check) is
// present with a null value. Types are checked by name on every read, so a
// plugin reading a need as the wrong type gets an error, not garbage.
#include <map>
#include <memory>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

namespace sb::plugin {

class DerivedData {
 public:
  template <class T>
  void put(const std::string& name, std::shared_ptr<const T> value) {
    entries_[name] = Entry{std::move(value), typeid(T).name()};
  }
  void put_check(const std::string& name) { entries_[name] = Entry{}; }
  bool has(const std::string& name) const { return entries_.count(name) != 0; }
  std::vector<std::string> names() const;

  // The need's data, or null when it was not derived; throws
  // std::logic_error when it holds another type.
  template <class T>
  const T* find(const std::string& name) const {
    const auto it = entries_.find(name);
    if (it == entries_.end() || !it->second.value) return nullptr;
    check_type(name, it->second.type, typeid(T).name());
    return static_cast<const T*>(it->second.value.get());
  }
  // As find(), but throws std::logic_error naming the need when absent: a
  // technique reading a need it did not declare.
  template <class T>
  const T& get(const std::string& name) const {
    const T* value = find<T>(name);
    if (value == nullptr) throw_absent(name);
    return *value;
  }

  // Adds every entry of `other` (GPU data beside the plan's CPU data).
  void merge(const DerivedData& other);

 private:
  struct Entry {
    std::shared_ptr<const void> value;
    std::string type;  // typeid(T).name(): equal across modules for one T
  };
  static void check_type(const std::string& name, const std::string& held,
                         const std::string& wanted);
  [[noreturn]] static void throw_absent(const std::string& name);
  std::map<std::string, Entry> entries_;
};

}  // namespace sb::plugin
