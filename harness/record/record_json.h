#pragma once
// A described record struct (record/describe.h) to its JSON and back: the
// writer and the reader every record type's to_json and from_json are.
//
// Written: a double through json_number (NaN and ±inf as strings), a
// member by its presence (an unset optional, or an empty one marked
// UnlessEmpty, is absent, never null). Read: through Fields, so that an
// error names the member's JSON pointer.
#include <string>
#include <utility>
#include <vector>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

template <Described S>
nlohmann::json write_record(const S& s, const std::string& suffix = "");
template <Described S>
void read_record_into(S& s, const Fields& f, const std::string& suffix = "");
template <Described S>
S read_record(const Fields& f, const std::string& suffix = "") {
  S s;
  read_record_into(s, f, suffix);
  return s;
}

namespace record_json_detail {

using describe_detail::NameMap;
using describe_detail::Numbers;
using describe_detail::Optional;

template <class T>
nlohmann::json value_json(const T& v, const std::string& suffix) {
  if constexpr (Described<T>) {
    return write_record(v, suffix);
  } else if constexpr (DescribedList<T>) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& e : v) out.push_back(write_record(e, suffix));
    return out;
  } else if constexpr (NameMap<T>::value) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [name, value] : v) out[name] = value_json(value, suffix);
    return out;
  } else if constexpr (std::is_same_v<T, double>) {
    return json_number(v);
  } else if constexpr (std::is_same_v<T, std::vector<double>> || Numbers<T>::value) {
    nlohmann::json out = nlohmann::json::array();
    for (const double x : v) out.push_back(json_number(x));
    return out;
  } else {
    return v;
  }
}

template <class T>
T value_of(const Fields& f, const std::string& key, const std::string& suffix) {
  if constexpr (Described<T>) {
    return read_record<T>(f.object(key), suffix);
  } else if constexpr (DescribedList<T>) {
    T out;
    for (const Fields& e : f.objects(key))
      out.push_back(read_record<typename describe_detail::List<T>::type>(e, suffix));
    return out;
  } else if constexpr (NameMap<T>::value) {
    const Fields members = f.object(key);
    T out;
    for (const std::string& name : members.keys())
      out[name] = value_of<typename NameMap<T>::type>(members, name, suffix);
    return out;
  } else if constexpr (Numbers<T>::value) {
    const std::vector<double> v = f.get<std::vector<double>>(key);
    if (v.size() != Numbers<T>::size)
      f.fail(key, "expected " + std::to_string(Numbers<T>::size) + " numbers");
    T out{};
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = v[i];
    return out;
  } else {
    return f.get<T>(key);
  }
}

// Whether an UnlessEmpty member is left out (a number never is).
template <class T>
bool is_empty(const T& v) {
  if constexpr (Described<T>)
    return write_record(v).empty();
  else if constexpr (requires { v.empty(); })
    return v.empty();
  else
    return false;
}

// The keys whose presence says that a flattened part is there: its members
// that every such part writes.
template <class S>
class RequiredKeys {
 public:
  std::vector<std::string> keys;
  template <class M>
  void field(const char* key, M S::* /*member*/, const FieldInfo& info = {}) {
    if (presence_of<M>(info.presence) == Presence::Always) keys.emplace_back(key);
  }
  template <class F>
  void object(const char* key, const FieldInfo& /*info*/, F&& /*members*/) {
    keys.emplace_back(key);
  }
  template <class T>
  void flatten(std::optional<T> S::* /*member*/, const FieldInfo& /*info*/) {}
  template <class W, class R>
  void custom(const char* key, const char* /*type*/, const FieldInfo& info, W&& /*write*/,
              R&& /*read*/) {
    if (info.presence == Presence::Always) keys.emplace_back(key);
  }
};

template <class S>
class Writer {
 public:
  Writer(const S& s, nlohmann::json& out, std::string suffix)
      : s_(s), out_(out), suffix_(std::move(suffix)) {}

  template <class M>
  void field(const char* key, M S::*member, const FieldInfo& info = {}) {
    const M& v = s_.*member;
    const std::string k = key_of(key, info, suffix_);
    if constexpr (Optional<M>::value) {
      if (v) out_[k] = value_json(*v, suffix_of(info));
    } else {
      if (info.presence == Presence::UnlessEmpty && is_empty(v)) return;
      out_[k] = value_json(v, suffix_of(info));
    }
  }
  template <class F>
  void object(const char* key, const FieldInfo& /*info*/, F&& members) {
    nlohmann::json sub = nlohmann::json::object();
    Writer w(s_, sub, suffix_);
    members(w);
    out_[key] = std::move(sub);
  }
  template <class T>
  void flatten(std::optional<T> S::*member, const FieldInfo& /*info*/) {
    if (!(s_.*member)) return;
    Writer<T> w(*(s_.*member), out_, suffix_);
    T::describe(w);
  }
  template <class W, class R>
  void custom(const char* key, const char* /*type*/, const FieldInfo& /*info*/, W&& write,
              R&& /*read*/) {
    if (std::optional<nlohmann::json> v = write(s_)) out_[key] = std::move(*v);
  }

 private:
  const S& s_;
  nlohmann::json& out_;
  std::string suffix_;
};

template <class S>
class Reader {
 public:
  Reader(S& s, const Fields& f, std::string suffix) : s_(s), f_(f), suffix_(std::move(suffix)) {}

  template <class M>
  void field(const char* key, M S::*member, const FieldInfo& info = {}) {
    const std::string k = key_of(key, info, suffix_);
    if constexpr (Optional<M>::value) {
      s_.*member = f_.has(k)
                       ? std::optional(value_of<typename Optional<M>::type>(f_, k, suffix_of(info)))
                       : std::nullopt;
    } else {
      const Presence p = presence_of<M>(info.presence);
      if (p == Presence::Always || f_.has(k)) s_.*member = value_of<M>(f_, k, suffix_of(info));
    }
  }
  template <class F>
  void object(const char* key, const FieldInfo& /*info*/, F&& members) {
    const Fields sub = f_.object(key);
    Reader r(s_, sub, suffix_);
    members(r);
  }
  template <class T>
  void flatten(std::optional<T> S::*member, const FieldInfo& /*info*/) {
    RequiredKeys<T> required;
    T::describe(required);
    bool any = false;
    for (const std::string& k : required.keys) any = any || f_.has(k);
    if (!any) return;
    T part;
    read_record_into(part, f_, suffix_);
    s_.*member = std::move(part);
  }
  template <class W, class R>
  void custom(const char* /*key*/, const char* /*type*/, const FieldInfo& /*info*/, W&& /*write*/,
              R&& read) {
    read(s_, f_);
  }

 private:
  S& s_;
  const Fields& f_;
  std::string suffix_;
};

}  // namespace record_json_detail

template <Described S>
nlohmann::json write_record(const S& s, const std::string& suffix) {
  nlohmann::json out = nlohmann::json::object();
  record_json_detail::Writer<S> w(s, out, suffix);
  S::describe(w);
  return out;
}

template <Described S>
void read_record_into(S& s, const Fields& f, const std::string& suffix) {
  record_json_detail::Reader<S> r(s, f, suffix);
  S::describe(r);
  if constexpr (requires { S::check(s, f); }) S::check(s, f);
}

}  // namespace sb::record
