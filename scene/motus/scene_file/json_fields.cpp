#include "motus/scene_file/json_fields.hpp"

#include "motus/scene_file/spelling.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

namespace motus {

std::string json_type_name(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::object: return "an object";
    default: return "a number";
  }
}

JsonFields::JsonFields(const nlohmann::json& object, std::string path, const NumberTexts* underflows)
    : object_(object), path_(std::move(path)), underflows_(underflows) {
  if (!object_.is_object()) throw SceneError(path_, "must be an object, not " + json_type_name(object_));
}

std::string JsonFields::path_of(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void JsonFields::fail(const std::string& key, const std::string& message) const {
  // A required field that is missing because it was misspelt ("mas" for "mass") is named as the
  // unknown field it is, with the guess reject_unknown would make, not as missing: the user wrote it.
  if (message.rfind("missing (required)", 0) == 0)
    if (const auto slip = misspelling_of(key))
      throw SceneError(path_of(*slip), "unknown field, did you mean " + key + "? (" + key + " is required)");
  throw SceneError(path_of(key), message);
}

std::optional<std::string> JsonFields::misspelling_of(const std::string& key) const {
  // The names asked for so far (and `key`), as reject_unknown lists them: a field of the object is
  // a slip for `key` when, by the same closeness rule, `key` is the known name nearest to it.
  std::vector<std::string> names = known_names();
  if (std::find(names.begin(), names.end(), key) == names.end()) names.push_back(key);
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (used_.count(it.key()) || std::find(names.begin(), names.end(), it.key()) != names.end()) continue;
    if (const auto guess = closest_known(it.key(), names); guess && *guess == key) return it.key();
  }
  return std::nullopt;
}

std::vector<std::string> JsonFields::known_names() const {
  std::vector<std::string> names;
  std::set<std::string> seen;
  for (const auto& k : asked_)
    if (seen.insert(k).second) names.push_back(k);
  return names;
}

bool JsonFields::has(const std::string& key) const {
  asked_.push_back(key);  // a key the reader looks for is a known one, for reject_unknown's list
  return object_.contains(key);
}

const nlohmann::json* JsonFields::find(const std::string& key) {
  asked_.push_back(key);
  auto it = object_.find(key);
  if (it == object_.end()) return nullptr;
  used_.insert(key);
  return &*it;
}

const nlohmann::json& JsonFields::at(const std::string& key) {
  if (const auto* v = find(key)) return *v;
  fail(key, "missing (required)");
}

namespace {

// Whether `text` is a word for a number JSON does not have: nan, inf, infinity (any case, a sign
// before it or not).
bool non_finite_word(std::string text) {
  const auto blank = [](unsigned char c) { return std::isspace(c) != 0; };
  while (!text.empty() && blank(static_cast<unsigned char>(text.back()))) text.pop_back();
  text.erase(text.begin(), std::find_if_not(text.begin(), text.end(), blank));
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) text.erase(0, 1);
  for (auto& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text == "nan" || text == "inf" || text == "infinity";
}

const char* const kNoSuchJsonNumber = ": JSON has no NaN or infinity";

}  // namespace

double JsonFields::checked_number(const nlohmann::json& value, const std::string& key) const {
  if (value.is_string()) {  // what --set makes of NaN, inf, ... (JSON itself has no such numbers)
    if (non_finite_word(value.get<std::string>()))
      fail(key, "must be a finite number (got " + value.get<std::string>() + ")" + kNoSuchJsonNumber);
  }
  if (!value.is_number()) fail(key, "must be a number, not " + json_type_name(value));
  const double x = value.get<double>();
  if (!std::isfinite(x)) fail(key, "must be a finite number");
  // (JSON's reader made 0 of a number too small for a double, without a word: the user did not write 0.)
  if (x == 0 && underflows_)
    if (const auto text = underflows_->find(path_of(key)); text != underflows_->end())
      fail(key, text->second + " is nearer 0 than the smallest double (4.9e-324), and would read as 0");
  return x;
}

double JsonFields::number(const std::string& key) { return checked_number(at(key), key); }
double JsonFields::number(const std::string& key, double fallback) {
  const auto* v = find(key);
  return v ? checked_number(*v, key) : fallback;
}

double JsonFields::checked_positive(const std::string& key, double x) const {
  if (!(x > 0)) fail(key, "must be > 0 (got " + nlohmann::json(x).dump() + ")");
  // A subnormal (below 2.2e-308) is > 0, but its inverse (1/m) is infinite.
  if (x < std::numeric_limits<double>::min())
    fail(key, "must be at least 2.2e-308, a double's smallest normal number (got " + nlohmann::json(x).dump() + ")");
  return x;
}
double JsonFields::positive(const std::string& key) {
  const double x = number(key);
  return checked_positive(key, x);
}
double JsonFields::positive(const std::string& key, double fallback) {
  const double x = number(key, fallback);
  return checked_positive(key, x);
}
double JsonFields::non_negative(const std::string& key) {
  const double x = number(key);
  if (!(x >= 0)) fail(key, "must be >= 0 (got " + nlohmann::json(x).dump() + ")");
  return x;
}
double JsonFields::non_negative(const std::string& key, double fallback) {
  const double x = number(key, fallback);
  if (!(x >= 0)) fail(key, "must be >= 0 (got " + nlohmann::json(x).dump() + ")");
  return x;
}

long JsonFields::integer(const std::string& key) {
  const double x = number(key);
  if (x != std::floor(x)) fail(key, "must be a whole number (got " + nlohmann::json(x).dump() + ")");
  if (std::abs(x) > 1e15) fail(key, "must be a whole number of at most 1e15 in size (got " + nlohmann::json(x).dump() + ")");
  return static_cast<long>(x);
}
long JsonFields::integer(const std::string& key, long fallback) {
  return has(key) ? integer(key) : fallback;
}

bool JsonFields::boolean(const std::string& key, bool fallback) {
  const auto* v = find(key);
  if (!v) return fallback;
  if (!v->is_boolean()) fail(key, "must be true or false, not " + json_type_name(*v));
  return v->get<bool>();
}

std::string JsonFields::string(const std::string& key) {
  const auto& v = at(key);
  if (!v.is_string()) fail(key, "must be a string, not " + json_type_name(v));
  return v.get<std::string>();
}
std::string JsonFields::string(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : fallback;
}

std::vector<double> JsonFields::numbers(const std::string& key, int size) {
  const auto& v = at(key);
  // --set's "[NaN, 0]" is no JSON, and came as that string: its NaN is named, as a number's would be.
  if (v.is_string()) {
    const std::string text = v.get<std::string>();
    const size_t open = text.find_first_not_of(" \t\n\r"), close = text.find_last_not_of(" \t\n\r");
    if (open != std::string::npos && text[open] == '[' && text[close] == ']') {
      size_t from = open + 1;
      for (size_t i = 0;; ++i) {
        const size_t comma = std::min(text.find(',', from), close);
        const std::string item = text.substr(from, comma - from);
        if (non_finite_word(item)) {
          const size_t begin = item.find_first_not_of(" \t\n\r"), end = item.find_last_not_of(" \t\n\r");
          fail(key + "[" + std::to_string(i) + "]",
               "must be a finite number (got " + item.substr(begin, end - begin + 1) + ")" + kNoSuchJsonNumber);
        }
        if (comma == close) break;
        from = comma + 1;
      }
    }
  }
  if (!v.is_array()) fail(key, "must be an array of numbers, not " + json_type_name(v));
  if (size >= 0 && static_cast<int>(v.size()) != size)
    fail(key, "must have " + std::to_string(size) + (size == 1 ? " number" : " numbers") + " (got " +
                  std::to_string(v.size()) + ")");
  std::vector<double> out;
  for (size_t i = 0; i < v.size(); ++i) out.push_back(checked_number(v[i], key + "[" + std::to_string(i) + "]"));
  return out;
}
std::vector<double> JsonFields::numbers(const std::string& key, int size, const std::vector<double>& fallback) {
  return has(key) ? numbers(key, size) : fallback;
}

JsonFields JsonFields::object(const std::string& key) {
  const auto& v = at(key);
  if (!v.is_object()) fail(key, "must be an object, not " + json_type_name(v));
  return JsonFields(v, path_of(key), underflows_);
}

std::vector<JsonFields> JsonFields::objects(const std::string& key) {
  std::vector<JsonFields> out;
  const auto* v = find(key);
  if (!v) return out;
  if (!v->is_array()) fail(key, "must be an array, not " + json_type_name(*v));
  for (size_t i = 0; i < v->size(); ++i) {
    const std::string item = path_of(key) + "[" + std::to_string(i) + "]";
    if (!(*v)[i].is_object()) throw SceneError(item, "must be an object, not " + json_type_name((*v)[i]));
    out.emplace_back((*v)[i], item, underflows_);
  }
  return out;
}

std::vector<std::string> JsonFields::keys() const {
  std::vector<std::string> k;
  for (auto it = object_.begin(); it != object_.end(); ++it) k.push_back(it.key());
  return k;
}

void JsonFields::reject_unknown() const {
  for (auto it = object_.begin(); it != object_.end(); ++it)
    if (!used_.count(it.key())) {
      const std::vector<std::string> names = known_names();
      std::string known;
      for (const auto& k : names) known += (known.empty() ? "" : ", ") + k;
      fail(it.key(), "unknown field" + did_you_mean(it.key(), names) +
                         (known.empty() ? std::string() : " (expected one of: " + known + ")"));
    }
}

}  // namespace motus
