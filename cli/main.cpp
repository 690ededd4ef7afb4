// motus: the command line of the coursework engine.
//   motus run SCENE ...               integrate a scene, report energy and momentum
//   motus list                        scenes, integrators, systems
//   motus bench precision SCENE ...   run time against error
//   motus render SCENE --out DIR ...  PNG frames (and a video) of a scene
//   motus stress SCENE ...            the stability stress test: tables and a page
//   motus compare SCENE ...           the scene in motus, Box2D and Bullet: tables, plots, a report
//   motus grade ASSIGNMENT DIR ...    a student's code graded in a sandbox (Gradescope's results)
//   motus serve --plugin FILE.so      (not for users) grade's server inside the sandbox
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <system_error>
#include <cstring>
#include <iostream>
#include <new>

#include <fcntl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include "bench_precision_command.hpp"
#include "compare_command.hpp"
#include "cli_common.hpp"
#include "locations.hpp"
#include "output_files.hpp"
#include "plugin_loading.hpp"
#include "command_line_errors.hpp"
#include "help_format.hpp"
#include "list_command.hpp"
#include "render_command.hpp"
#include "motus/collide/too_many_collisions.hpp"
#include "motus/scene_error.hpp"
#include "grade_command.hpp"
#include "interrupt.hpp"
#include "run_command.hpp"
#include "serve_command.hpp"
#include "stress_command.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace {

int motus_main(int argc, char** argv) {
  using namespace motus::cli;
  CLI::App app{
      "motus: a game-physics engine for teaching that tells the truth about its numbers.\n"
      "It integrates the scenes in scenes/ with the integrators of the course (docs/course.md) and reports\n"
      "energy, momentum and accuracy. Exit status: 0 done, 1 the run failed, 2 bad input.",
      "motus"};
  // (Before the commands are added: they take the formatter they are given then.)
  app.formatter(std::make_shared<WrappingFormatter>(help_width()));
  app.require_subcommand(1);
  app.set_version_flag("--version", "motus " MOTUS_VERSION);

  RunOptions run_options;
  auto* run = add_run_command(app, run_options);
  CompareOptions compare_options;
  auto* compare = add_compare_command(app, compare_options);
  std::vector<std::string> list_plugins;
  auto* list = add_list_command(app, list_plugins);
  auto* bench = app.add_subcommand("bench", "Benchmarks: `motus bench precision SCENE` (run time against error)");
  bench->require_subcommand(1);
  BenchPrecisionOptions precision_options;
  auto* precision = add_bench_precision_command(*bench, precision_options);
  RenderOptions render_options;
  auto* render = add_render_command(app, render_options);
  GradeCommandOptions grade_options;
  auto* grade = add_grade_command(app, grade_options);
  ServeOptions serve_options;
  auto* serve = add_serve_command(app, serve_options);
  StressOptions stress_options;
  auto* stress = add_stress_command(app, stress_options);
  // (After the commands: a command takes its parent's footer when it is added.)
  app.footer("motus COMMAND --help (or motus help COMMAND) tells about one command.");

  // Help and the version, printed: a standard output that could not take them (a full disk) is
  // a failure, as for every other output.
  auto printed = [](int status) {
    std::cout.flush();
    if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
      tell("motus: the run failed: standard output: could not be written ({})\n", std::strerror(errno));
      return kExitFailure;
    }
    return status;
  };
  // `motus help [COMMAND...]` is `motus [COMMAND...] --help` (and `motus help help` is `motus --help`).
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && args.front() == "help") {
    args.erase(args.begin());
    if (!args.empty() && args.front() == "help") args.erase(args.begin());
    if (const auto extra = word_after_help(app, args)) {
      tell("motus: error: {}\n", *extra);
      return kExitBadInput;
    }
    args.push_back("--help");
  }
  // (CLI11 prints the version and stops before it sees what follows.)
  if (args.size() > 1 && args.front() == "--version") {
    tell("motus: error: --version: takes nothing after it (got \"{}\")\n", one_line(args[1], 80));
    return kExitBadInput;
  }
  // Nothing at all: what there is to do, and a failure (nothing was done).
  if (args.empty()) {
    tell("{}\nmotus: error: a command is needed (motus COMMAND --help tells about one)\n", app.help());
    return kExitBadInput;
  }
  // A word that is no command, or an option before any command: CLI11 would say "A subcommand
  // is required", as if nothing had been given.
  if (const auto wrong = misplaced_word(app, args)) {
    tell("motus: error: {}\n", *wrong);
    return kExitBadInput;
  }
  try {
    std::reverse(args.begin(), args.end());  // (CLI11 takes the arguments last first)
    app.parse(args);
  } catch (const CLI::CallForHelp& e) {
    return printed(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return printed(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return printed(app.exit(e));
  } catch (const CLI::ParseError& e) {
    tell("motus: error: {}\n", parse_error_line(app, e));
    return kExitBadInput;
  }

  catch_interrupts();
  // A file-size limit (`ulimit -f`) then makes a write past it fail with EFBIG, which the writes'
  // checks report (exit 1, one line naming the file) and clean up after, instead of SIGXFSZ ending
  // motus without a word and leaving its partial files. Not in `serve`: the student's code runs in
  // it, and the sandbox names that signal ("wrote more than its 64 MB to a file").
  if (!*serve) ::signal(SIGXFSZ, SIG_IGN);
  // (serve: the grader reports a student's exit() from its sandbox.)
  watch_plugin_exits(!*serve);
  // What an interrupt left: rows streamed to standard output are the user's to keep (that file was
  // never motus's to take back); every file motus was writing went with the unwinding.
  const auto interrupted_exit = [&] {
    if (run->parsed() && run_options.trajectory == "-")
      tell("motus: interrupted; the trajectory on standard output stops where the run did, without the final state\n");
    else
      tell("motus: interrupted; nothing half-written was left behind\n");
    return kExitInterrupted;
  };
  int status = 0;
  try {
    if (*run) status = run_command(run_options);
    else if (*compare) status = compare_command(compare_options);
    else if (*list) status = list_command(list_plugins);
    else if (*precision) status = bench_precision_command(precision_options);
    else if (*render) status = render_command(render_options);
    else if (*grade) status = grade_command(grade_options);
    else if (*serve) status = serve_command(serve_options);
    else if (*stress) status = stress_command(stress_options);
    // Whatever went to standard output must have got there (a full disk is a failure, not 0).
    if (std::fflush(stdout) != 0 || std::ferror(stdout) || std::fflush(data_output()) != 0 || std::ferror(data_output())) {
      tell("motus: the run failed: standard output: could not be written ({})\n", std::strerror(errno));
      return kExitFailure;
    }
    // A Ctrl-C that came once the command had finished changes nothing it wrote: its files are
    // whole and in place (it said "nothing half-written was left behind" of a file just written).
    if (interrupted() && status == 0) tell("motus: interrupted once the work was done: everything was written\n");
    return status;
  } catch (const Interrupted&) {
    return interrupted_exit();
  } catch (const motus::SceneFileError& e) {
    tell("motus: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const motus::SceneError& e) {
    // Raised while building the run (e.g. a symplectic integrator on a first-order system).
    const std::string scene = find_scene_path(run->parsed()       ? run_options.scene
                                              : compare->parsed() ? compare_options.scene
                                              : stress->parsed()  ? stress_options.scene
                                                                  : precision_options.scene);
    tell("motus: error: {}\n", one_line(scene + ": " + (e.field().empty() ? "" : e.field() + ": ") + e.what()));
    return kExitBadInput;
  } catch (const motus::TooManyCollisions& e) {
    // The run itself failed (exit 1), at the step its message names: which scene's, said first
    // (it read "the run failed: more than 2600 collisions in one step: …" with no file).
    if (interrupted()) return interrupted_exit();
    const std::string scene = find_scene_path(run->parsed()       ? run_options.scene
                                              : compare->parsed() ? compare_options.scene
                                              : render->parsed()  ? render_options.scene
                                              : stress->parsed()  ? stress_options.scene
                                                                  : precision_options.scene);
    tell("motus: the run failed: {}\n", one_line(scene + ": " + e.what()));
    return kExitFailure;
  } catch (const InputError& e) {
    tell("motus: error: {}\n", one_line(named_as_final(e.what())));
    return kExitBadInput;
  } catch (const motus::ExternalError& e) {
    // A plug-in's function failed (it threw): the plug-in is bad input, not motus.
    std::string files;
    for (const auto& p : plugins().plugins()) files += (files.empty() ? "" : ", ") + p.file;
    tell("motus: error: {}\n", one_line((files.empty() ? "plug-in" : files) + ": " + e.what()));
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    // Memory ran out (a limit such as `ulimit -v`, or the machine's): one line saying so and what
    // to make smaller; what was being written went with the unwinding (the partial folders).
    if (interrupted()) return interrupted_exit();
    tell("motus: the run failed: out of memory (the system refused an allocation): {}\n",
         compare->parsed() ? "run fewer bodies (a smaller --set lattice.count=N, say), fewer --engines at once, a "
                             "shorter --duration or fewer --samples, or allow motus more memory"
         : render->parsed() ? "run fewer bodies, a shorter --duration, a lower --fps or a smaller --size, or allow "
                              "motus more memory"
                            : "run fewer bodies or a shorter --duration, or allow motus more memory");
    return kExitFailure;
  } catch (const std::exception& e) {
    if (interrupted()) return interrupted_exit();  // (a program motus waited for died of the same Ctrl-C)
    const std::string what = e.what();
    if (std::ferror(stdout) && what.rfind("standard output", 0) != 0) {  // fmt's "cannot write to file" is standard output's: named as such
      const auto* system = dynamic_cast<const std::system_error*>(&e);
      tell("motus: the run failed: standard output: could not be written ({})\n",
                 system ? system->code().message() : one_line(e.what()));
      return kExitFailure;
    }
    tell("motus: the run failed: {}\n", one_line(named_as_final(e.what())));  // (a temporary folder is gone)
    return kExitFailure;
  }
}

}  // namespace

// Standard input, output and error closed by the caller (`>&-`) would be the first files motus
// opens: a trajectory opened as descriptor 2 took the progress bar's lines, as descriptor 1 the
// summary's. Each closed one is held by /dev/null instead, standard output read-only, so that
// writing to it still fails (EBADF) and the run says so, as it did when it was closed.
void hold_closed_standard_descriptors() {
  for (const int fd : {0, 1, 2})
    if (::fcntl(fd, F_GETFD) == -1 && errno == EBADF) {
      const int held = ::open("/dev/null", fd == 2 ? O_WRONLY : O_RDONLY);
      if (held >= 0 && held != fd) {  // (an earlier descriptor was open after all: put it where it belongs)
        ::dup2(held, fd);
        ::close(held);
      }
    }
}

int main(int argc, char** argv) {
  hold_closed_standard_descriptors();
  const int status = motus_main(argc, argv);
  motus::cli::main_is_returning();  // (an exit() in a plug-in's code does not come this way)
  return status;
}
