// Reading validated JSON input (scenarios, device configurations): every error names the
// source and the dotted field path ("case.json: solver.dt: must be > 0, got -0.001") and
// is thrown as ScenarioError (the command line's exit code 2). Readers of one format
// derive from JsonReader and add their own fields.
#pragma once

#include <cmath>
#include <vector>
#include <set>
#include <sstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "scenario.h"  // ScenarioError

namespace palpation::sim {

class JsonReader {
 public:
  using json = nlohmann::json;
  /// comments: keys starting with "_" are comments, not unknown keys.
  explicit JsonReader(std::string source, bool comments = false) : source_(std::move(source)), comments_(comments) {}

  [[noreturn]] void fail(const std::string& field, const std::string& why) const {
    std::string msg = source_ + ": " + (field.empty() ? std::string("(top level)") : field) + ": " + why;
    // Keys and values from the file are quoted in messages: a control character in them
    // (a newline in a key, found by fuzzing, docs/fuzzing.md) must not break the line.
    for (char& c : msg)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    throw ScenarioError(msg);
  }
  static std::string join(const std::string& a, const std::string& b) { return a.empty() ? b : a + "." + b; }

  /// The document of `text`; malformed JSON (and a number too large for a double,
  /// "1e999", found by fuzzing: docs/fuzzing.md) fails as "(syntax)" with where and why.
  json parse(const std::string& text) const {
    try {
      return json::parse(text);
    } catch (const json::parse_error& e) {
      fail("(syntax)", "malformed JSON at byte " + std::to_string(e.byte) + ": " + library_message(e.what()));
    } catch (const json::exception& e) {
      fail("(syntax)", library_message(e.what()));
    }
  }
  /// nlohmann's message without its "[json.exception...]" and "parse error at ...:" prefixes,
  /// at most 200 characters.
  static std::string library_message(const std::string& what) {
    std::string s = what.substr(what.find(']') == std::string::npos ? 0 : what.find(']') + 1);
    if (!s.empty() && s[0] == ' ') s.erase(0, 1);
    if (s.rfind("parse error at ", 0) == 0 && s.find(": ") != std::string::npos) s = s.substr(s.find(": ") + 2);
    if (s.size() > 200) s = s.substr(0, 200) + "...";
    return s;
  }
  static std::string fmt(double d) {
    std::ostringstream o;
    o << d;
    return o.str();
  }

  void only_keys(const json& obj, const std::string& field, std::initializer_list<const char*> keys) const {
    if (!obj.is_object()) fail(field, "must be an object");
    const std::set<std::string> allowed(keys.begin(), keys.end());
    for (auto it = obj.begin(); it != obj.end(); ++it)
      if (!allowed.count(it.key()) && !(comments_ && it.key().rfind('_', 0) == 0)) {
        std::string list;
        for (const char* k : keys) list += std::string(list.empty() ? "" : ", ") + k;
        fail(join(field, it.key()), "unknown key (allowed: " + list + ")");
      }
  }
  /// Calls f(value, field) when the object has the key.
  template <class F>
  void opt(const json& o, const char* key, const std::string& field, F&& f) const {
    if (o.contains(key)) f(o.at(key), join(field, key));
  }

  double number(const json& v, const std::string& field) const {
    if (!v.is_number()) fail(field, "must be a number, got " + std::string(v.type_name()));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(field, "must be finite");
    return d;
  }
  double positive(const json& v, const std::string& field) const {
    const double d = number(v, field);
    if (!(d > 0)) fail(field, "must be > 0, got " + fmt(d));
    return d;
  }
  double non_negative(const json& v, const std::string& field) const {
    const double d = number(v, field);
    if (d < 0) fail(field, "must be >= 0, got " + fmt(d));
    return d;
  }
  int integer(const json& v, const std::string& field, int lo, int hi) const {
    if (!v.is_number_integer()) fail(field, "must be an integer");
    const auto i = v.get<long long>();
    if (i < lo || i > hi) fail(field, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(i);
  }
  std::string string(const json& v, const std::string& field) const {
    if (!v.is_string()) fail(field, "must be a string");
    return v.get<std::string>();
  }
  std::string choice(const json& v, const std::string& field, const std::vector<std::string>& options) const {
    const std::string s = string(v, field);
    std::string list;
    for (const auto& o : options) {
      if (s == o) return s;
      list += (list.empty() ? "" : ", ") + o;
    }
    fail(field, "must be one of " + list + ", got \"" + s + "\"");
  }
  /// Three numbers, as T{x, y, z}.
  template <class T>
  T triple(const json& v, const std::string& field) const {
    if (!v.is_array() || v.size() != 3) fail(field, "must be an array of 3 numbers");
    return T{number(v[0], field + "[0]"), number(v[1], field + "[1]"), number(v[2], field + "[2]")};
  }

 private:
  std::string source_;
  bool comments_ = false;
};

}  // namespace palpation::sim
