#pragma once
// The parts of the strict JSON reading (strict_json.cpp) that the scene reader uses too: the SAX pass
// that names a failure's field path and refuses what strict_json.hpp refuses (parse_scene runs it on each
// --set value), and parse_strict_json keeping the numbers that read as 0 though they are not.
#include <algorithm>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "motus/scene_file/json_fields.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace motus {

// Where in the document a parse failed, as a field path: a SAX pass that keeps the
// path of keys and indices and stops at the error nlohmann reports — or at a key an object
// already has, or at nesting deeper than kMaxNesting (checked before the document is built,
// so ten million '[' cost nothing).
class FieldPathTracker : public nlohmann::json::json_sax_t {
public:
  std::string path() const {
    std::string p;
    for (const auto& frame : stack_) {
      if (frame.is_array) {
        if (frame.index >= 0) p.append(1, '[').append(std::to_string(frame.index)).append(1, ']');
      } else if (!frame.key.empty()) {
        if (!p.empty()) p += '.';
        p += frame.key;
      }
    }
    return p;
  }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t x, const string_t& text) override {
    if (!value()) return false;
    // (A number whose digits are not all 0 that reads as 0: its exponent is below a double's.)
    const auto mantissa_end = text.begin() + static_cast<std::ptrdiff_t>(std::min(text.find_first_of("eE"), text.size()));
    if (x == 0 && underflows_ && std::any_of(text.begin(), mantissa_end, [](char c) { return c >= '1' && c <= '9'; }))
      (*underflows_)[path()] = text;
    return true;
  }
  // Where number_float writes the numbers that read as 0 though they are not (none: not kept).
  void keep_underflows(NumberTexts* underflows) { underflows_ = underflows; }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    if (!advance()) return false;
    stack_.push_back({false, -1, "", {}});
    return deep_enough();
  }
  bool key(string_t& k) override {
    if (!stack_.back().keys.insert(k).second) {
      problem_ = "duplicate key \"" + k + "\": a key may appear once in an object (which one would count?)";
      stack_.back().key = k;
      return false;
    }
    stack_.back().key = k;
    return true;
  }
  // The parser stopped between two members of the innermost object or array (after a comma,
  // at a '}' or ']'): the key or index last read is not where it stopped, so it is not named.
  void forget_last_member() {
    if (stack_.empty()) return;
    stack_.back().key.clear();
    stack_.back().index = -1;
  }
  // Why the pass stopped early ("" : it did not, or nlohmann's own error).
  const std::string& problem() const { return problem_; }
  bool end_object() override { return end(); }
  bool start_array(std::size_t) override {
    if (!advance()) return false;
    stack_.push_back({true, -1, "", {}});
    return deep_enough();
  }
  bool end_array() override { return end(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception&) override { return false; }

private:
  struct Frame {
    bool is_array;
    long index;
    std::string key;
    std::set<std::string> keys;  // an object's keys so far
  };
  bool deep_enough() {
    if (static_cast<int>(stack_.size()) <= kMaxNesting) return true;
    problem_ = "nested more than " + std::to_string(kMaxNesting) + " arrays or objects deep";
    return false;
  }
  std::string problem_;
  NumberTexts* underflows_ = nullptr;
  // One more element of the innermost array. The scene's own lists of bodies and sticks are
  // counted here, before the document is built: a million bodies and one more are refused now,
  // not after a gigabyte of document.
  bool advance() {
    if (stack_.empty() || !stack_.back().is_array) return true;
    const long count = ++stack_.back().index + 1;
    if (stack_.size() == 2 && !stack_[0].is_array) {
      const std::string& list = stack_[0].key;
      const long limit = list == "bodies" ? kMaxBodies : list == "sticks" ? kMaxSticks : 0;
      if (limit > 0 && count > limit) {
        problem_ = "more than " + std::to_string(limit) + " " + list + " (the limit of a scene's " + list + ")";
        return false;
      }
    }
    return true;
  }
  bool value() { return advance(); }
  bool end() {
    stack_.pop_back();
    return true;
  }
  std::vector<Frame> stack_;
};

// parse_strict_json, keeping in `underflows` (when given) the numbers that read as 0 though they are not.
nlohmann::json parse_strict_json(const std::string& text, const std::string& file, NumberTexts* underflows);

}  // namespace motus
