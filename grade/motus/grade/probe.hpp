#pragma once
// The grader's side of the probe protocol (wire.hpp): a student's plug-in served by
// `motus serve` in a sandbox. A check asks it for raw outputs; when the student's code fails
// (it threw, crashed, looped or ran out of memory) the request throws ProbeFailure saying
// what happened, and a dead server is started again for the next check.
#include <chrono>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/grade/sandbox.hpp"

namespace motus::grade {

class ProbeFailure : public std::runtime_error {
public:
  explicit ProbeFailure(const std::string& what, bool out_of_time = false, bool stopped_the_run = false,
                        bool printed_a_lot = false)
      : std::runtime_error(what), out_of_time_(out_of_time), stopped_the_run_(stopped_the_run),
        printed_a_lot_(printed_a_lot) {}
  // It timed out or used up its CPU (rather than crashed, threw or ran out of memory).
  bool out_of_time() const { return out_of_time_; }
  // It ran out of time after printing a lot (Ending::printed_a_lot): the likelier cause, which
  // `what` names first.
  bool printed_a_lot() const { return printed_a_lot_; }
  // The run ended with an error, the process did not: a step of 0 or NaN, a step-size control
  // that never shrinks, an exception — wrong numbers, which the test's hint is about.
  bool stopped_the_run() const { return stopped_the_run_; }

private:
  bool out_of_time_, stopped_the_run_, printed_a_lot_;
};

// A reply that has not the shape its request asks for — not JSON, a key missing or of the wrong
// type, rows of the wrong size, longer than the request can need: the student's code can write
// over the server's answers (docs/grading.md, "The sandbox"), so this fails that one test, with
// "WHOSE was malformed: WHY" ("the run's reply was malformed: …"), and never the grader.
[[noreturn]] void malformed_reply(const std::string& whose, const std::string& why);

// The most an answer may hold: this many numbers (a run's rows × its state's size, say), and room
// for its keys and brackets. A longer one is refused, as malformed, and one of more values as soon
// as its parse counts them: a 63 MB reply held 1.1 GB of the grader's memory as a parsed document.
// (A reply that says the code failed may be longer, up to 16 MB: it carries the student's own
// exception's message.)
struct ReplySize {
  size_t numbers = 256;  // (a call's or a step's few outputs)
  size_t bytes() const;  // 32 per number (the longest a double or "-inf" takes, with its comma), and 64 kB
  size_t values() const;  // the JSON values a parse may make: numbers, and the rows and keys around them
};

struct ProbeSetup {
  std::string motus;   // the motus executable (this one), mounted read-only
  std::string plugin;  // the student's plug-in, mounted read-only
  // Files mounted read-only beside motus, where it looks for its modules: the expressions module
  // (a test's scene may have an equations system).
  std::vector<std::string> modules;
  std::function<bool()> stop;  // Ctrl-C: see SandboxSpec::stop
  Limits limits;
  bool isolate = true;
  uid_t uid = 0;  // the sandbox's user
};

class Probe {
public:
  explicit Probe(ProbeSetup setup);
  ~Probe();

  // One request and its reply, a JSON object whose "ok" is true; throws ProbeFailure (a reply
  // larger than `size` allows, or not such an object, is malformed_reply's). The deadline is the check's.
  nlohmann::json ask(nlohmann::json request, std::chrono::steady_clock::time_point deadline, ReplySize size = {});
  // Stops the server (and everything it started), its output read to the end: what the student's
  // code printed in it is kept for printed().
  void stop();
  // What the student's code printed (its standard output and error) in the server stopped last, as
  // a paragraph of a test's output — "What your code printed during this test:" and it, or the end
  // of it, cut as a crash's output is — and forgets it. "" when it printed nothing, or when a
  // failure's message has shown it already (a crash, a timeout).
  std::string printed();

private:
  void start();
  [[noreturn]] void died(const std::string& while_doing);

  ProbeSetup setup_;
  std::unique_ptr<SandboxProcess> server_;
  std::string printed_;  // (as SandboxProcess::errors keeps it: at most Limits::output_bytes, its first and last halves)
  std::chrono::steady_clock::time_point started_;
  bool serving_ = false;  // the current server has said wire::kServing (the student's code is loaded after)
};

}  // namespace motus::grade
