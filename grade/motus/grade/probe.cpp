#include "motus/grade/probe.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "motus/grade/wire.hpp"

namespace motus::grade {
namespace {
// The most of a student's error message a test's output keeps (of what their code printed: kShownBytes).
constexpr size_t kMessageBytes = 2000;
// The most of what the student's code printed a test's output shows: its last bytes.
constexpr size_t kShownBytes = 1200;
// The longest reply that says the student's code failed: its exception's message, cut to
// kMessageBytes for the test's output (8 MB of message is the student's own doing, not a forgery).
constexpr size_t kFailureReplyBytes = size_t(16) << 20;

// What the student's code printed — its standard output and error as the sandbox kept them (past
// its cap, the first half and the last, "…" between) — for a test's output: "" when it printed
// nothing but white space, else a heading and the text ("Its output:", say, with `what` "its
// output"), or the text's last kShownBytes after "The end of its output:" — the prints just before
// the test went wrong. A crash's message and a failed test's prints are both shown so.
std::string shown_output(std::string text, const std::string& what) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (text.empty()) return "";
  const bool cut = text.size() > kShownBytes;
  if (cut) {
    // From a character's first byte: UTF-8's continuation bytes are 10xxxxxx (cut at one, a
    // character would show as U+FFFD, the replacement character).
    size_t from = text.size() - kShownBytes;
    while (from < text.size() && (static_cast<unsigned char>(text[from]) & 0xC0) == 0x80) ++from;
    text = "…" + text.substr(from);
  }
  std::string heading = cut ? "the end of " + what : what;
  heading[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(heading[0])));
  return heading + ":\n" + text;
}
}  // namespace

void malformed_reply(const std::string& whose, const std::string& why) { throw ProbeFailure(whose + " was malformed: " + why); }

size_t ReplySize::bytes() const {
  return static_cast<size_t>(std::min(32.0 * static_cast<double>(numbers) + 65536.0, static_cast<double>(SandboxProcess::kMaxLineBytes)));
}

size_t ReplySize::values() const {
  return static_cast<size_t>(std::min(1.5 * static_cast<double>(numbers) + 4096.0, static_cast<double>(SandboxProcess::kMaxLineBytes)));
}

Probe::Probe(ProbeSetup setup) : setup_(std::move(setup)) {}

Probe::~Probe() { stop(); }

void Probe::start() {
  SandboxSpec spec;
  spec.isolate = setup_.isolate;
  spec.stop = setup_.stop;
  spec.uid = setup_.uid;
  spec.writable_tmp = false;  // (the student's code answers on its output; it has no file to write)
  if (setup_.isolate) {
    spec.mounts = {{setup_.motus, "/motus/motus", false}, {setup_.plugin, "/box/student.so", false}};
    for (const auto& m : setup_.modules)
      spec.mounts.push_back({m, "/motus/" + std::filesystem::path(m).filename().string(), false});
    spec.argv = {"/motus/motus", "serve", "--plugin", "/box/student.so"};
  } else {
    spec.argv = {setup_.motus, "serve", "--plugin", setup_.plugin};
  }
  server_ = std::make_unique<SandboxProcess>(spec, setup_.limits);
  started_ = std::chrono::steady_clock::now();
  serving_ = false;
}

void Probe::stop() {
  // Its input closed, the server ends by itself (and bubblewrap with it); only one that does
  // not is killed. Either way its output has been read to its end (what std::cout held unflushed
  // included, when it ended by itself).
  if (server_) {
    server_->finish(std::chrono::steady_clock::now() + std::chrono::seconds(1));
    printed_ = server_->errors();
  }
  server_.reset();
}

std::string Probe::printed() {
  const std::string shown =
      shown_output(printed_, "what your code printed during this test");
  printed_.clear();
  return shown;
}

void Probe::died(const std::string& while_doing) {
  // At the test's deadline (the wall-clock backstop), or gone by itself (then given 2 s to end).
  const bool at_deadline = server_->timed_out();
  Ending ending = at_deadline ? server_->kill()
                              : server_->finish(std::chrono::steady_clock::now() + std::chrono::seconds(2));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  double seconds = wall;
  if (at_deadline) {
    // Whether it was too slow, waiting, or never given a core: the last is the machine's failure.
    const double cpu = cpu_limit_seconds(setup_.limits.cpu_seconds);
    ending.verdict = judge_wall_timeout(ending.use, cpu);
    if (*ending.verdict == WallVerdict::starved) {
      server_.reset();
      throw MachineTooBusy(starved_message("the student's code", ending.use, cpu));
    }
    seconds = wall_backstop(setup_.limits.cpu_seconds);  // (as the result says it: the same on any machine)
  }
  // Before the server said it serves (wire::kServing), none of the student's code had run: what
  // ended it is the sandbox's or the server's, never the code's. (bubblewrap's own failure says
  // "bwrap: …" and exits 1; it read as the student's code exiting with status 1. That alone, not
  // the moment, was the rule before, and a submission that printed "bwrap: " and exited 1 itself
  // made its grading the grader's failure, every time.)
  if (!serving_) {
    const std::string& said = server_->errors();
    const std::string why = !said.empty() ? said.substr(0, said.find('\n')) : "it " + ending.describe(setup_.limits, seconds);
    server_.reset();
    throw std::runtime_error("the sandbox could not start the student's code's server: " + why);
  }
  const bool out_of_time = ending.out_of_time(setup_.limits, seconds);
  std::string what = "your code " + ending.describe(setup_.limits, seconds);
  if (!while_doing.empty()) what += " during " + while_doing;
  // The last lines it wrote on standard error (and standard output, which goes there too): shown
  // here, so not again below the test's output (printed_ does not get them).
  const std::string shown = shown_output(server_->errors(), "its output");
  if (!shown.empty()) what += ". " + shown;
  server_.reset();  // the next request starts a new one
  throw ProbeFailure(what, out_of_time, false, out_of_time && ending.printed_a_lot(setup_.limits));
}

nlohmann::json Probe::ask(nlohmann::json request, std::chrono::steady_clock::time_point deadline, ReplySize size) {
  if (!server_) start();
  const std::string op = request.value("op", std::string("?"));
  // What the student's code was doing, by the names the student wrote: the wire's operations are
  // the plug-in's (balls_impact is the student's time_of_impact).
  const std::string integrator = request.value("integrator", std::string());
  const bool theirs = integrator.rfind("student:", 0) == 0;
  const std::string doing = op == "run"            ? (theirs ? "a run of the scene with your integrator " + integrator
                                                             : std::string("a run of the scene"))
                            : op == "step"         ? "a step of your integrator " + integrator
                            : op == "project"      ? "satisfy_constraints"
                            : op == "balls_impact" ? "time_of_impact"
                            : op == "plane_impact" ? "time_of_impact_with_plane"
                                                   : op;
  const std::string whose = op == "run" ? "the run's reply" : "the reply of " + doing;
  if (!serving_) {  // (its first line, written before the student's code was loaded: wire.hpp)
    const auto hello = server_->read_line(deadline, wire::kServing.size() + 1);
    if (!hello && server_->interrupted()) {
      server_->kill();
      server_.reset();
      throw GradingInterrupted();
    }
    if (!hello) died(doing);
    if (*hello != wire::kServing) {
      server_->kill();
      server_.reset();
      throw std::runtime_error("the student's code's server began with \"" + hello->substr(0, 80) + "\", not " +
                               std::string(wire::kServing));
    }
    serving_ = true;
  }
  const bool written =
      server_->write_line(request.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), deadline);
  // (Read as far as a failure's reply may go: it carries the student's exception's message, of any
  // length, which a run's numbers do not bound. An answer is held to its own size below.)
  const size_t most_bytes = std::max(size.bytes(), kFailureReplyBytes);
  const auto line = written ? server_->read_line(deadline, most_bytes) : std::nullopt;
  if (!line && server_->interrupted()) {
    server_->kill();
    server_.reset();
    throw GradingInterrupted();
  }
  if (!line && server_->line_too_long()) {
    // (Read no further: the server is ended, what it printed kept for the test's output.)
    server_->kill();
    printed_ = server_->errors();
    server_.reset();
    malformed_reply(whose, "longer than " + std::to_string(most_bytes) + " bytes, more than this request can need");
  }
  if (!line) died(doing);
  // Parsed with a count of its values: within the bytes, a reply of 0s would still make a document
  // 16 times its size.
  nlohmann::json reply;
  struct TooMany {};
  size_t values = 0;
  const size_t most = size.values();
  try {
    reply = nlohmann::json::parse(*line, [&](int depth, nlohmann::json::parse_event_t event, nlohmann::json&) {
      if (event != nlohmann::json::parse_event_t::object_end && event != nlohmann::json::parse_event_t::array_end &&
          (++values > most || depth > 8))
        throw TooMany{};
      return true;
    });
  } catch (const TooMany&) {
    malformed_reply(whose, "more than " + std::to_string(most) + " JSON values, or nested deeper than 8, more than this request can need");
  } catch (const std::exception&) {
    // A whole line that is not JSON: the code wrote over the server's answers (the server itself
    // writes only JSON). Said as such: taken for the server's death, it read "your code exited with
    // status 0", as it went on to end when its input closed. Its start shown, printable bytes only.
    std::string start;
    for (const char c : line->substr(0, 40)) start += c >= ' ' && c <= '~' ? c : '?';
    malformed_reply(whose, "not JSON (it began \"" + start + (line->size() > 40 ? "…" : "") + "\")");
  }
  // Every key read as what it must be: a missing "ok", or an "error" that is no string, threw
  // nlohmann's out_of_range or type_error, which the grader took for a fault of its own.
  if (!reply.is_object()) malformed_reply(whose, "not a JSON object");
  const auto ok = reply.find("ok");
  if (ok == reply.end() || !ok->is_boolean()) malformed_reply(whose, "no \"ok\": true or false");
  if (ok->get<bool>() && line->size() > size.bytes())
    malformed_reply(whose, "longer than " + std::to_string(size.bytes()) + " bytes, more than this request can need");
  if (!ok->get<bool>()) {
    const auto error_at = reply.find("error"), threw_at = reply.find("threw");
    if (error_at != reply.end() && !error_at->is_string()) malformed_reply(whose, "its \"error\" is not a string");
    if (threw_at != reply.end() && !threw_at->is_boolean()) malformed_reply(whose, "its \"threw\" is not true or false");
    const bool threw = threw_at != reply.end() && threw_at->get<bool>();
    // The student's own words (an exception's message), cut as its output is: 8 MB of them went
    // whole into results.json.
    std::string error = error_at != reply.end() ? error_at->get<std::string>() : std::string("failed");
    if (error.size() > kMessageBytes) {
      size_t cut = kMessageBytes;
      while (cut > 0 && (static_cast<unsigned char>(error[cut]) & 0xC0) == 0x80) --cut;  // (not inside a UTF-8 character)
      error = error.substr(0, cut) + "… (cut: " + std::to_string(error.size()) + " bytes in all)";
    }
    // The memory limit shows up as a failed allocation in the student's code.
    if (error.find("std::bad_alloc") != std::string::npos)
      throw ProbeFailure("your code ran out of its " + std::to_string(setup_.limits.memory_mb) + " MB (" + error + ")");
    // An exception of the student's own is no wrong number: the test's hint would not be about it.
    if (threw) throw ProbeFailure("your code stopped the run: " + error);
    throw ProbeFailure("your code stopped the run: " + error, false, true);
  }
  return reply;
}

}  // namespace motus::grade
