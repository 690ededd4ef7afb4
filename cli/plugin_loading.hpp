#pragma once
// The plug-ins this process loads (--plugin FILE.so), and standard output kept apart from what
// their code prints: the data a program reads, the timing runs' prints, a plug-in's exit().
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "motus/plugin/plugin_set.hpp"

namespace motus::cli {

// The plug-ins of this process (--plugin FILE.so, repeatable on run, render, compare,
// bench precision and list), loaded by load_plugins.
PluginSet& plugins();
// Adds --plugin to a subcommand.
void add_plugin_option(CLI::App* command, std::vector<std::string>& files);

// Where run and compare write data that a program reads (--json, run's --trajectory -): standard
// output, unless a plug-in was loaded while it carried such data. A plug-in's code runs in this
// process and shares descriptor 1, so its printf or std::cout would land between a CSV's rows or
// inside the JSON object; load_plugins(files, true) then points descriptor 1 at standard error
// for everyone, the plug-in's prints and motus's own messages alike, and the data go to a copy of
// what standard output was. (serve keeps its answers apart the same way, before the sandbox's
// filter is installed: keep_data_apart_from_standard_output.)
std::FILE* data_output();
// Makes data_output() a copy of descriptor 1 and points descriptor 1 at standard error (once; later
// calls return the same copy). Throws std::runtime_error when it cannot.
std::FILE* keep_data_apart_from_standard_output();

// While begun, descriptor 1 writes to /dev/null: the timing runs after the one reported, so that
// what a plug-in's code prints on standard output comes once, with the run it belongs to, not
// once more per timing run. (Standard error, the progress bar's, is left alone.)
class QuietStandardOutput {
public:
  QuietStandardOutput() = default;
  QuietStandardOutput(const QuietStandardOutput&) = delete;
  QuietStandardOutput& operator=(const QuietStandardOutput&) = delete;
  ~QuietStandardOutput() { end(); }
  void begin();
  void end();

private:
  int saved_ = -1;  // descriptor 1 as it was
};
// A plug-in's code that calls exit() ends motus with the status it gives: exit(0) read as a run
// that went well and said nothing, its folders half-written. motus itself never calls exit, so
// once a plug-in is loaded (when watch_plugin_exits(true) was called: not in serve, whose grader
// reports it) an atexit handler makes any exit that main's return did not make one line naming
// the plug-ins, and exit 1. main calls main_is_returning() as it returns.
void watch_plugin_exits(bool watch);
void main_is_returning();

// Loads them, in order, and from then on reports a crash in their code; a file that is not
// a usable plug-in is an InputError (one line, exit 2). `data_on_standard_output`: the command
// writes data for a program there (see data_output).
void load_plugins(const std::vector<std::string>& files, bool data_on_standard_output = false);

}  // namespace motus::cli
