#include "grade_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <ctime>
#include <filesystem>
#include <optional>
#include <mutex>
#include <thread>

#include "cli_common.hpp"
#include "locations.hpp"
#include "option_values.hpp"
#include "output_files.hpp"
#include "interrupt.hpp"
#include "gradescope_package.hpp"
#include "motus/grade/grader.hpp"
#include "progress_bar.hpp"

namespace fs = std::filesystem;

namespace motus::cli {
namespace {

// ASSIGNMENT: a folder with an assignment.json, or the name of one under the assignments folder.
std::string assignment_folder(const std::string& argument) {
  // ("…/integrators/" is the folder integrators: its name names the results and the runs/ folder)
  if (fs::is_regular_file(looked_at((fs::path(argument) / "assignment.json").string())))
    return without_trailing_separators(argument).string();
  if (argument.find('/') == std::string::npos) {
    const fs::path shipped = fs::path(assignments_directory()) / argument;
    if (fs::is_regular_file(looked_at((shipped / "assignment.json").string()))) return shipped.string();
  }
  std::string known;
  std::error_code error;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(assignments_directory(), error))
    if (std::error_code ignored; fs::is_regular_file(e.path() / "assignment.json", ignored))
      names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  if (known.empty())
    throw InputError(argument + ": no such assignment (a folder with an assignment.json), and none is shipped in " +
                     assignments_directory() + " (set MOTUS_ASSIGNMENTS to the folder of the assignments)");
  throw InputError(argument + ": no such assignment (a folder with an assignment.json; shipped: " + known + ")");
}

grade::GradeOptions grade_options(const GradeCommandOptions& o) {
  grade::GradeOptions g;
  g.motus = executable_path();
  // The expressions module, for a test whose scene has an equations system (the sandbox holds
  // only what is mounted in it).
  for (const auto& m : module_candidates("MOTUS_EXPRESSIONS_MODULE", MOTUS_EXPRESSIONS_MODULE_NAME,
                                         MOTUS_EXPRESSIONS_MODULE_INSTALLED))
    if (fs::is_regular_file(m)) {
      g.modules.push_back(m);
      break;
    }
  g.headers = {student_api_directory("student"), student_api_directory("plugin"), student_api_directory("external")};
  g.limits.cpu_seconds = o.time_limit;
  g.limits.memory_mb = o.memory_limit;
  g.isolate = !o.no_sandbox;
  g.stop = [] { return interrupted(); };  // Ctrl-C ends the wait for a student's code or its compiler at once
  return g;
}

// Hidden tests the sandbox would show the student's code: under /usr (bound read-only into every
// sandbox) or a folder of the student API headers, however the path is spelt (links followed).
void check_hidden_out_of_sight(const std::string& hidden) {
  std::error_code error;
  const fs::path where = fs::canonical(hidden, error);
  if (error) return;  // (is_directory said it is there)
  const grade::ApiHeaders headers{student_api_directory("student"), student_api_directory("plugin"),
                                  student_api_directory("external")};
  for (const std::string& shown : grade::folders_in_sight(headers)) {
    const fs::path folder = fs::canonical(shown, error);
    if (error) continue;
    const fs::path inside = where.lexically_relative(folder);
    if (!inside.empty() && *inside.begin() != "..")
      throw InputError(hidden + ": --hidden: is under " + shown + ", which the sandbox shows the student's code (read-only): "
                       "it could read the hidden tests; keep them elsewhere, readable by the grader only");
  }
}

grade::Assignment load(const GradeCommandOptions& o, const std::string& folder) {
  if (o.hidden) {
    const auto hidden = looked_at(*o.hidden, "--hidden");
    if (fs::exists(hidden) && !fs::is_directory(hidden)) throw InputError(*o.hidden + ": --hidden: is a file, not a folder");
    if (!fs::is_directory(hidden)) throw InputError(*o.hidden + ": --hidden: no such folder");
  }
  // (Not for --package: the zip takes a copy, which Gradescope keeps in the autograder's own folder.)
  if (o.hidden && o.package.empty()) check_hidden_out_of_sight(*o.hidden);
  grade::SceneSource scenes;
  scenes.shipped = [](const std::string& name) { return find_scene_path(name); };
  scenes.guess = [](const std::string& name) { return shipped_scene_guess(name); };
  try {
    return grade::load_assignment(folder, o.hidden, scenes);
  } catch (const grade::AssignmentError& e) {
    throw InputError(e.what());
  }
}

// The limits a grading takes, checked for --package too: its run_autograder passes them on, and
// out of range every student's grading on Gradescope would fail.
void check_limit_ranges(const GradeCommandOptions& o) {
  // (Below half a second a correct solution can time out: each test starts a server of its own,
  // and the longer tests take tenths of a second of the reference solution's own time.)
  if (!(o.time_limit >= 0.5) || o.time_limit > 600) throw InputError("--time-limit: must be from 0.5 to 600 s");
  if (o.memory_limit < 64 || o.memory_limit > 65536) throw InputError("--memory-limit: must be from 64 to 65536 MB");
}

void check_limits(const GradeCommandOptions& o) {
  check_limit_ranges(o);
  if (o.jobs && (*o.jobs < 1 || *o.jobs > 64)) throw InputError("--jobs: must be from 1 to 64");
  if (!o.no_sandbox)
    if (const auto why = grade::sandbox_unavailable()) throw InputError(*why);
}

std::string new_folder(const std::string& prefix) {
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  std::string path = fmt::format("runs/{}-{}", prefix, stamp);
  for (int i = 2; output_exists(path); ++i) path = fmt::format("runs/{}-{}-{}", prefix, stamp, i);
  return path;
}

// What stops the grading of one submission before it starts still leaves --results a results.json
// that says why, once that file is known to be writable: on Gradescope a missing one shows every
// student only "the autograder failed" (a container without user namespaces, where bubblewrap
// cannot make a sandbox, is the likely cause there).
void write_not_graded(const GradeCommandOptions& o, const std::string& assignment, const std::string& why) {
  if (o.results.empty() || o.results == "-") return;
  try {
    check_can_replace(o.results, o.overwrite);
    write_whole_file(o.results, grade::results_text(grade::failed_json(assignment, why)), o.overwrite);
  } catch (const std::exception&) {
    // (the error that stopped the grading is the one to tell)
  }
}

// The assignment and the machine, checked before a submission is graded; what stops it here
// still leaves a results.json (write_not_graded).
grade::Assignment ready_to_grade(const GradeCommandOptions& o, const std::string& folder) {
  try {
    const auto submission = looked_at(o.submission);
    if (fs::is_regular_file(submission)) {
      // An archive is unpacked first; any other file (the handout's integrators.cpp itself, as a
      // student audit gave it) is in the folder to give instead.
      const bool archive = grade::looks_packed(fs::path(o.submission).filename().string());
      const fs::path parent = fs::path(o.submission).parent_path();
      throw InputError(o.submission + ": is a file; a submission is the folder of the handout's files " +
                       (archive ? std::string("(unpack it first)")
                                : "(give the folder that holds it: " + (parent.empty() ? std::string(".") : parent.string()) + ")"));
    }
    if (!fs::is_directory(submission)) throw InputError(o.submission + ": no such submission folder");
    grade::Assignment assignment = load(o, folder);
    check_limits(o);
    return assignment;
  } catch (const InputError& e) {
    write_not_graded(o, fs::path(folder).filename().string(), e.what());
    throw;
  }
}

int grade_one(const GradeCommandOptions& o, const std::string& folder) {
  // (`motus run --trajectory -` writes to standard output; here a file called "-" was made.)
  for (const auto& [option, path] : {std::pair{"--results", &o.results}, std::pair{"--plugin-out", &o.plugin_out}})
    if (*path == "-")
      throw InputError(std::string(option) + " -: standard output is the summary's; give the file a name");
  if (!o.results.empty()) check_can_replace(o.results, o.overwrite);
  if (!o.plugin_out.empty()) check_can_replace(o.plugin_out, o.overwrite);
  if (!o.results.empty() && !o.plugin_out.empty()) {
    // Made absolute first: weakly_canonical keeps a relative path as typed when its first part
    // does not exist ("same.json"), but makes it absolute when it does ("adir/../same.json"): the
    // two spellings of one file compared unequal, the grading ran, and its end failed (exit 1).
    auto where = [](const std::string& path, std::error_code& error) {
      const fs::path absolute = fs::absolute(path, error);
      return error ? absolute : fs::weakly_canonical(absolute, error);
    };
    std::error_code a, b;
    const fs::path results = where(o.results, a), plugin = where(o.plugin_out, b);
    if (!a && !b && results == plugin)
      throw InputError(o.plugin_out + ": --plugin-out: is --results's file too; give them two files");
  }
  const grade::Assignment assignment = ready_to_grade(o, folder);
  grade::GradeOptions options = grade_options(o);
  std::optional<PartialFile> plugin_out;  // (kept only when the submission compiles)
  if (!o.plugin_out.empty()) options.plugin_out = plugin_out.emplace(o.plugin_out).path();
  ProgressBar progress(0, static_cast<double>(assignment.tests.size()), "grade " + assignment.name, 1);
  // The compile takes seconds before any test (9–11 s for integrators): it is named while it runs.
  options.building = [&] { progress.note("compiling the submission"); };
  options.progress = [&](size_t done, size_t total, const std::string& test) {
    // The tests' phase from the first on: the time to go is from their rate, not the compile's.
    if (done == 0) progress.phase("testing", 0, static_cast<double>(total));
    progress.step(test);
    progress.update(static_cast<double>(done));
  };
  // The grader asks whether to stop at least ten times a second while it waits for the compiler or a
  // test: the bar is redrawn then, so that its seconds go on and a test that started within a tenth
  // of a second of the last redraw is still named while it runs.
  options.stop = [&progress, stop = options.stop] {
    progress.refresh();
    return stop && stop();
  };
  grade::GradeResult result;
  try {
    result = grade::grade_submission(assignment, o.submission, options);
    progress.finish();
  } catch (const Interrupted&) {
    throw;  // (Ctrl-C: no results, exit 130)
  } catch (const grade::GradingInterrupted&) {
    throw Interrupted();
  } catch (const std::exception& e) {
    // Even now, a valid results.json that says what happened.
    if (!o.results.empty()) write_whole_file(o.results, grade::results_text(grade::failed_json(assignment.name, e.what())), o.overwrite);
    throw;
  }
  const std::string json = grade::results_text(grade::gradescope_json(result));
  if (!o.results.empty()) write_whole_file(o.results, json, o.overwrite);
  if (plugin_out && result.compiled) plugin_out->complete(o.overwrite);
  if (!o.plugin_out.empty() && !result.compiled)
    tell("motus: note: --plugin-out: {} was not written: the submission does not compile\n", o.plugin_out);
  if (o.format.value_or("text") == "gradescope")
    fmt::print("{}", json);
  else
    fmt::print("{}", grade::text_summary(result));
  return 0;
}

// A submission's folder name as one CSV field (RFC 4180: quoted when it holds a comma, a quote or
// a line break, quotes doubled). A name a spreadsheet would take for a formula (=, +, -, @ first)
// is prefixed with ' so that it opens as the text it is: the names come from the students.
std::string csv_field(const std::string& name) {
  std::string field = grade::terminal_safe(name);  // (an escape sequence is no name's: '?')
  if (!field.empty() && std::string("=+-@\t\r").find(field[0]) != std::string::npos) field = "'" + field;
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string quoted = "\"";
  for (const char c : field) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

int grade_batch(const GradeCommandOptions& o, const std::string& folder) {
  const auto batch = looked_at(o.batch, "--batch");
  if (fs::exists(batch) && !fs::is_directory(batch)) throw InputError(o.batch + ": --batch: is a file, not a folder of submissions");
  if (!fs::is_directory(batch)) throw InputError(o.batch + ": --batch: no such folder");
  const std::string out = o.out.empty() ? new_folder("grade-" + safe_file_name(fs::path(folder).filename().string())) : o.out;
  if (output_exists(out)) throw InputError(out + ": --out: already exists; grading never writes over earlier results");
  const grade::Assignment assignment = load(o, folder);
  check_limits(o);
  // More jobs than cores: not wrong (each test's CPU limit still holds, and its wall clock has room
  // for the wait), but every test waits for a core, and a test starved past that room is the
  // grader's failure (exit 1), not the student's.
  if (const int cores = grade::available_cores(); o.jobs && *o.jobs > cores)
    tell("motus: warning: --jobs {} is more than this machine's {} core{}: tests will wait for a core, and take longer\n",
         *o.jobs, cores, cores == 1 ? "" : "s");
  std::vector<fs::path> submissions;
  std::error_code listing;
  for (fs::directory_iterator e(o.batch, listing), end; !listing && e != end; e.increment(listing))
    if (fs::is_directory(looked_at(e->path().string(), "--batch"))) submissions.push_back(e->path());
  if (listing) throw InputError(o.batch + ": --batch: " + listing.message());
  std::sort(submissions.begin(), submissions.end());
  if (submissions.empty()) throw InputError(o.batch + ": --batch: has no submission folders");
  // Written as .OUT.partial-XXXXXX and renamed when whole: Ctrl-C or a failure leaves no folder
  // that looks like a finished batch (the scores.csv of it all is written last).
  PartialFolder folder_of_results(out);
  const std::string written = folder_of_results.path();

  struct Row {
    double score = 0, max_score = 0, seconds = 0;
    std::string status;
    bool results_written = false;  // (a full disk can refuse even the file that says the grader failed)
  };
  std::vector<Row> rows(submissions.size());
  std::atomic<size_t> next{0}, done{0};
  std::mutex failures_lock;
  std::vector<std::string> failures;
  ProgressBar progress(0, static_cast<double>(submissions.size()), "grade " + assignment.name, 1);
  const auto began = std::chrono::steady_clock::now();
  auto worker = [&] {
    const grade::GradeOptions options = grade_options(o);  // (each grading takes a sandbox user of its own)
    for (size_t i = next++; i < submissions.size() && !interrupted(); i = next++) {
      const std::string name = submissions[i].filename().string();
      const std::string results = (fs::path(written) / (name + ".json")).string();
      try {
        const auto result = grade::grade_submission(assignment, submissions[i].string(), options);
        write_whole_file(results, grade::results_text(grade::gradescope_json(result)), false);  // (a folder of our own)
        rows[i] = {result.score, result.max_score, result.seconds,
                   !result.tests[0].passed ? "missing files" : !result.compiled ? "does not compile" : "graded", true};
      } catch (const grade::GradingInterrupted&) {
        break;  // (Ctrl-C: the main thread says so)
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(failures_lock);
        failures.push_back(name + ": " + e.what());
        rows[i] = {0, assignment.max_score(), 0, "grader failed"};
        try {
          write_whole_file(results, grade::results_text(grade::failed_json(assignment.name, e.what())), false);
          rows[i].results_written = true;
        } catch (...) {
        }
      }
      ++done;
    }
  };
  std::vector<std::jthread> threads;  // (joined however this function is left: never std::terminate)
  const int jobs = o.jobs.value_or(1);
  for (int j = 0; j < std::min<int>(jobs, static_cast<int>(submissions.size())); ++j) threads.emplace_back(worker);
  while (done < submissions.size() && !interrupted()) {
    try {
      progress.update(static_cast<double>(done));
    } catch (const Interrupted&) {
      break;  // (not with the workers still running: they stop at the flag, and are joined below)
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (auto& t : threads) t.join();  // (after Ctrl-C each ends its sandbox at once)
  // The submissions graded so far keep their results (each took its seconds of grading): the
  // folder is kept without a scores.csv, which only a whole batch has. Nothing graded: no folder.
  // The submissions whose results file was written, and those of the rest that were graded (or
  // failed) without one: a message that says "kept" names only what is there.
  size_t kept_count = 0;
  std::string unwritten;
  for (size_t i = 0; i < submissions.size(); ++i) {
    kept_count += rows[i].results_written;
    if (!rows[i].results_written && !rows[i].status.empty())
      unwritten += (unwritten.empty() ? "" : ", ") + csv_field(submissions[i].filename().string());
  }
  auto tell_failures = [&] {
    for (const auto& f : failures) {
      std::string line = grade::terminal_safe(named_as_final(f));  // (a student's folder name and an error: one line)
      std::replace(line.begin(), line.end(), '\n', ' ');
      tell("motus: the grader failed on {}\n", line);
    }
  };
  auto keep_what_was_graded = [&]() -> std::string {  // where they are now ("": nothing to keep)
    if (kept_count == 0) return "";
    try {
      return folder_of_results.complete();
    } catch (const std::exception&) {
      return written;  // (--out appeared meanwhile: the folder stays where it was written)
    }
  };
  if (interrupted()) {
    progress.finish();
    const std::string kept = keep_what_was_graded();
    if (kept.empty()) tell("motus: interrupted before any submission was graded; nothing was written\n");
    else tell("motus: interrupted; the {} graded so far {} in {}/ (no scores.csv: the batch is not whole){}; to grade "
              "the batch again, give another --out\n",
              kept_count == 1 ? "1 submission" : std::to_string(kept_count) + " submissions",
              kept_count == 1 ? "has its results" : "have their results", kept,
              unwritten.empty() ? "" : "; no results file could be written for " + unwritten);
    return kExitInterrupted;
  }
  progress.finish();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();

  std::string csv = "submission,score,max_score,seconds,status\n";
  for (size_t i = 0; i < submissions.size(); ++i)
    csv += fmt::format("{},{},{},{:.2f},{}\n", csv_field(submissions[i].filename().string()), rows[i].score, rows[i].max_score,
                       rows[i].seconds, rows[i].status);
  try {
    write_whole_file((fs::path(written) / "scores.csv").string(), csv, false);
  } catch (const std::exception& e) {
    tell_failures();
    const std::string kept = keep_what_was_graded();
    const std::string what = one_line(e.what()) + (kept.empty() ? "; no submission's results could be written"
                                                                : "; the results of " + std::to_string(kept_count) + " of the " +
                                                                      std::to_string(submissions.size()) +
                                                                      " submissions are kept in " + kept + "/ (no scores.csv)");
    throw std::runtime_error(what + (unwritten.empty() || kept.empty() ? "" : "; none could be written for " + unwritten));
  }
  const std::string results_folder = folder_of_results.complete();  // (as named: "out/" is out)
  fmt::print("{}", csv);
  tell("motus: graded {} submissions of {} in {:.1f} s with {} job{}; results in {}/\n", submissions.size(),
             assignment.name, wall, jobs, jobs == 1 ? "" : "s", results_folder);
  tell_failures();
  return failures.empty() ? 0 : kExitFailure;
}

}  // namespace

CLI::App* add_grade_command(CLI::App& app, GradeCommandOptions& o) {
  auto* g = app.add_subcommand("grade",
                               "Grade a submission of an assignment in a sandbox: Gradescope's results.json and a "
                               "readable summary (see docs/grading.md)");
  g->add_option("assignment", o.assignment, "An assignment: a folder under assignments/ (integrators, collisions, cloth) or a path")
      ->required();
  g->add_option("submission", o.submission, "The submission's folder (the files the handout names)");
  g->add_option("--results", o.results, "Write Gradescope's results.json here")->check(non_empty_path());
  g->add_option("--format", o.format, "What standard output shows: text (a summary; the default) or gradescope (the JSON)")
      ->check(CLI::IsMember({"text", "gradescope"}));
  g->add_option("--hidden", o.hidden, "The folder of hidden tests (the instructor's; not given: only the public tests run)");
  g->add_option("--time-limit", o.time_limit, "Seconds of CPU each test may take, 0.5 to 600 (whole seconds, rounded up; its wall clock is a backstop: 2 x this + 5 s)")->capture_default_str();
  g->add_option("--memory-limit", o.memory_limit, "Megabytes of address space the student's code may use, 64 to 65536 (its server can start no other process)")->transform(read_as_decimal())->capture_default_str();
  g->add_flag("--no-sandbox", o.no_sandbox,
              "Grade without bubblewrap (limits and another user only): for machines without user namespaces, knowingly");
  g->add_option("--plugin-out", o.plugin_out, "Also keep the plug-in built from the submission here (for motus run --plugin)")->check(non_empty_path());
  g->add_flag("--overwrite", o.overwrite, "Allow --results and --plugin-out to replace existing files");
  g->add_option("--batch", o.batch, "Grade every subfolder of this folder, one submission each");
  g->add_option("--jobs", o.jobs, "With --batch: submissions graded at once, 1 to 64 (default 1)")->transform(read_as_decimal());
  g->add_option("--out", o.out, "With --batch: the results folder (default: a new folder under runs/); with --package: the zip")->check(folder_path("folder (--batch) or zip (--package)"));
  g->add_option("--package", o.package, "Write the autograder zip for this platform instead of grading")
      ->check(CLI::IsMember({"gradescope"}));
  return g;
}

int grade_command(const GradeCommandOptions& o) {
  std::string folder;
  try {
    folder = assignment_folder(o.assignment);
  } catch (const InputError& e) {
    // An unknown assignment is bad input like a missing submission folder: one submission's
    // --results still says so (it wrote none).
    if (!o.submission.empty() && o.batch.empty() && o.package.empty())
      write_not_graded(o, without_trailing_separators(o.assignment).filename().string(), e.what());
    throw;
  }
  const int modes = !o.submission.empty() + !o.batch.empty() + !o.package.empty();
  if (modes > 1)
    throw InputError("grade: a SUBMISSION_DIR, --batch and --package are three ways to use it: give one of them, not " +
                     std::string(!o.submission.empty() ? "SUBMISSION_DIR" : "--batch") + " and " +
                     (!o.package.empty() ? "--package" : "--batch"));
  if (modes != 1) throw InputError("grade: give a SUBMISSION_DIR, or --batch DIR, or --package gradescope --out FILE.zip");
  // An option the chosen use would silently ignore is refused.
  const std::string use = !o.package.empty() ? "with --package" : !o.batch.empty() ? "with --batch" : "with one SUBMISSION_DIR";
  auto refuse = [&](bool given, const std::string& option, const std::string& instead) {
    if (given) throw InputError(option + ": has no use " + use + " (" + instead + ")");
  };
  if (o.submission.empty()) {
    refuse(!o.results.empty(), "--results", !o.batch.empty() ? "each submission's results are written in --out" : "the zip grades into Gradescope's results");
    refuse(!o.plugin_out.empty(), "--plugin-out", "it keeps one submission's plug-in");
    refuse(o.format.has_value(), "--format", !o.batch.empty() ? "standard output is the scores' CSV" : "nothing is graded here");
  } else {
    refuse(!o.out.empty(), "--out", "it is --batch's folder or --package's zip; --results names the results file");
  }
  if (o.batch.empty()) refuse(o.jobs.has_value(), "--jobs", "it is --batch's");
  if (!o.package.empty()) {
    if (o.out.empty()) throw InputError("--package: needs --out FILE.zip");
    check_limit_ranges(o);
    const grade::Assignment assignment = load(o, folder);  // checked before it is packed
    const int status = write_gradescope_package(folder, assignment.name, o.hidden, o.out, o.no_sandbox, o.time_limit,
                                                o.memory_limit, o.overwrite);
    // In the words of the grading's summary ("11 of the instructor's tests not run here: 9 shown
    // after the due date, 2 never shown"): "the rubric's 11 hidden tests" read as 11 of visibility
    // hidden, where the rubric has 2 (and 9 after_due_date).
    if (!o.hidden && assignment.hidden_not_given > 0) {
      const std::string when = assignment.not_given_when();
      tell("motus: note: no --hidden: the autograder grades the public tests only; {} of the rubric's tests {} not "
           "among them (the instructor's, given with --hidden: {}) and {} left out; the scores are then out of {} points\n",
           assignment.hidden_not_given, assignment.hidden_not_given == 1 ? "is" : "are", when,
           assignment.hidden_not_given == 1 ? "is" : "are", assignment.max_score());
    }
    return status;
  }
  if (!o.batch.empty()) return grade_batch(o, folder);
  return grade_one(o, folder);
}

}  // namespace motus::cli
