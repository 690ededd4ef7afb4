#pragma once
// Reading one JSON object field by field, knowing where we are: every error names the
// field's path ("bodies[2].mass"), every field nobody asked for is reported as unknown.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "motus/scene_error.hpp"

namespace motus {

// The numbers of a document that read as 0 though their text is not zero (1e-400: below the smallest
// double), by field path ("bodies[0].mass") to the text as written: JSON's reader makes them 0 without a
// word, and the loader refuses them, as it refuses 1e999.
using NumberTexts = std::map<std::string, std::string>;

class JsonFields {
public:
  // `underflows`, when given, names the numbers that read as 0 though they are not (the fields made by
  // object() and objects() share it).
  JsonFields(const nlohmann::json& object, std::string path, const NumberTexts* underflows = nullptr);

  // Fields: required ones throw when missing; optional ones return the default.
  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  double positive(const std::string& key);                   // > 0 (and not subnormal)
  double positive(const std::string& key, double fallback);
  double non_negative(const std::string& key);                   // ≥ 0
  double non_negative(const std::string& key, double fallback);
  long integer(const std::string& key);
  long integer(const std::string& key, long fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  // An array of exactly `size` finite numbers (any size when size < 0).
  std::vector<double> numbers(const std::string& key, int size);
  std::vector<double> numbers(const std::string& key, int size, const std::vector<double>& fallback);
  bool has(const std::string& key) const;
  // Sub-objects and arrays of objects, each with its own path.
  JsonFields object(const std::string& key);
  std::vector<JsonFields> objects(const std::string& key);
  // Every key of this object (for maps such as a system's parameters).
  std::vector<std::string> keys() const;

  // Throws for the first field that no call above asked for.
  void reject_unknown() const;

  const std::string& path() const { return path_; }
  // The object itself, for a field read by hand; use(key) then marks that field as read.
  const nlohmann::json& raw() const { return object_; }
  void use(const std::string& key) { find(key); }
  std::string path_of(const std::string& key) const;
  // (A message "missing (required)…" for a field the object has misspelt becomes that field's
  // "unknown field, did you mean KEY? (KEY is required)".)
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

private:
  const nlohmann::json& at(const std::string& key);
  const nlohmann::json* find(const std::string& key);
  double checked_number(const nlohmann::json& value, const std::string& key) const;
  double checked_positive(const std::string& key, double x) const;
  // The names asked for so far, each once, in the order first asked: the fields this object may have.
  std::vector<std::string> known_names() const;
  // A field of this object, not asked for, that is a likely misspelling of `key` (for a missing required field).
  std::optional<std::string> misspelling_of(const std::string& key) const;

  const nlohmann::json& object_;
  std::string path_;
  const NumberTexts* underflows_ = nullptr;
  std::set<std::string> used_;      // keys read
  mutable std::vector<std::string> asked_;  // keys asked for (or tested with has), present or not, in order
};

// "a number", "a string", "an array", ... for messages.
std::string json_type_name(const nlohmann::json& value);

}  // namespace motus
