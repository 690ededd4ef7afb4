#pragma once
// An assignment as the grader reads it from its folder (assignments/README.md, "For
// instructors"):
//   assignment.json  name, title, the files a student hands in ("files"), the assignment's own
//                    files compiled with them ("provided": the header, plugin.cpp), extra
//                    compiler flags, and the tests an untouched starter passes
//   rubric.json      every test's name, points and visibility (Gradescope's: visible,
//                    after_due_date, after_published, hidden)
//   tests/*.json     the public tests; hidden/*.json (or --hidden DIR) the instructor's others
// Each test: {"name", "title", "kind", "hint", "catches": [mistakes], "counts_with_one_of": [public
// tests], ...its kind's fields}.
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/grade/check.hpp"

namespace motus::grade {

// An assignment folder that cannot be used: "FILE: FIELD: MESSAGE".
class AssignmentError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct TestCase {
  std::string name, title, hint;
  std::vector<std::string> catches;  // the mistakes it is there to catch (seeded-bug tests check them)
  // A test whose right answer is also what code that does nothing gives (no contact: infinity; a
  // stick left alone) counts only when the same code passes one of these public tests too: an
  // untouched starter scored points for doing nothing.
  std::vector<std::string> counts_with_one_of;
  std::string file;                  // the definitions file it came from
  bool hidden = false;               // from the hidden tests
  double points = 0;
  std::string visibility = "visible";
  std::unique_ptr<Check> check;
};

struct Assignment {
  std::string name, title, folder;
  std::vector<std::string> files;     // handed in, as the handout names them
  std::vector<std::string> provided;  // the assignment's own, compiled with them
  std::vector<std::string> flags;     // extra compiler flags
  std::vector<std::string> starter_passes;  // tests an untouched starter passes (by design)
  std::string timeout_hint;           // what a test that runs out of time usually means (its own hint else)
  std::vector<TestCase> tests;        // in rubric order; only those whose definitions were given
  long hidden_not_given = 0;          // rubric entries skipped because no hidden tests were given
  long hidden_shown_later = 0;        // of those, the ones students see after the due date (or publishing)
  // Of those, how many of each visibility: visible, after_due_date, after_published, hidden.
  std::map<std::string, long> not_given_by_visibility;
  StudentParts parts;                 // what the assignment's plug-in brings (its plugin.cpp)
  double max_score() const;
  // When students see the tests not given, by visibility: "2 shown after the due date, 1 once the
  // grades are published, 2 never shown" ("" when every test was given).
  std::string not_given_when() const;
};

// What the plug-in the assignment provides brings (its MOTUS_PLUGIN's registrations, read from
// the source of the `provided` files in `folder`); not known when no provided file holds one, or
// its calls are not all of plain string literals.
StudentParts read_plugin_parts(const std::string& folder, const std::vector<std::string>& provided);

// Reads the folder; `hidden` is the folder of hidden tests (none: only the public ones run).
// Throws AssignmentError.
Assignment load_assignment(const std::string& folder, const std::optional<std::string>& hidden,
                           const SceneSource& scenes);

}  // namespace motus::grade
