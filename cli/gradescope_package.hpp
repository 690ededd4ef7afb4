#pragma once
// `motus grade ASSIGNMENT --package gradescope --out autograder.zip`: the zip Gradescope's
// autograder takes (setup.sh and run_autograder at its root). setup.sh installs the Debian
// packages of motus's package list and builds motus from the sources in the zip;
// run_autograder grades /autograder/submission into /autograder/results/results.json.
// The root (/autograder) and the motus that grades can be moved with $AUTOGRADER_ROOT and
// $MOTUS_BINARY, so that a test can run the zip end to end in a temporary folder.
#include <optional>
#include <string>

namespace motus::cli {

int write_gradescope_package(const std::string& assignment_folder, const std::string& assignment_name,
                             const std::optional<std::string>& hidden, const std::string& zip, bool no_sandbox,
                             double time_limit, long memory_limit, bool overwrite);

}  // namespace motus::cli
