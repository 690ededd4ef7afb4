#include "motus/grade/probe.hpp"

#include <filesystem>

namespace motus::grade {
namespace {
// The most of a student's error message a test's output keeps (their output's end is cut to 1200).
constexpr size_t kMessageBytes = 2000;
}  // namespace

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
}

void Probe::stop() {
  // Its input closed, the server ends by itself (and bubblewrap with it); only one that does
  // not is killed.
  if (server_) server_->finish(std::chrono::steady_clock::now() + std::chrono::seconds(1));
  server_.reset();
}

void Probe::died(const std::string& while_doing) {
  const Ending ending = server_->timed_out() ? server_->kill()
                                             : server_->finish(std::chrono::steady_clock::now() + std::chrono::seconds(2));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  const double seconds = server_->timed_out() ? setup_.limits.cpu_seconds : wall;
  const bool out_of_time = ending.out_of_time(setup_.limits, seconds);
  std::string what = "your code " + ending.describe(setup_.limits, seconds);
  if (!while_doing.empty()) what += " during " + while_doing;
  // The last lines it wrote on standard error (and standard output, which goes there too).
  std::string errors = server_->errors();
  if (!errors.empty()) {
    // Only its first 64 KB are kept (the rest was read and dropped): past that, "the end" is
    // the end of what was kept, not what it wrote last.
    const bool capped = errors.size() >= setup_.limits.output_bytes, cut = errors.size() > 1200;
    if (cut) errors = "…" + errors.substr(errors.size() - 1200);
    while (!errors.empty() && (errors.back() == '\n' || errors.back() == ' ')) errors.pop_back();
    what += capped ? ". The end of the first " + std::to_string(setup_.limits.output_bytes / 1024) + " KB of its output:\n"
            : cut  ? ". The end of its output:\n"
                   : ". Its output:\n";
    what += errors;
  }
  server_.reset();  // the next request starts a new one
  throw ProbeFailure(what, out_of_time);
}

nlohmann::json Probe::ask(nlohmann::json request, std::chrono::steady_clock::time_point deadline) {
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
  const bool written =
      server_->write_line(request.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), deadline);
  const auto line = written ? server_->read_line(deadline) : std::nullopt;
  if (!line && server_->interrupted()) {
    server_->kill();
    server_.reset();
    throw GradingInterrupted();
  }
  if (!line) died(doing);
  nlohmann::json reply;
  try {
    reply = nlohmann::json::parse(*line);
  } catch (const std::exception&) {
    died(doing);
  }
  if (!reply.value("ok", false)) {
    // The student's own words (an exception's message), cut as its output is: 8 MB of them went
    // whole into results.json.
    std::string error = reply.value("error", std::string("failed"));
    if (error.size() > kMessageBytes) {
      size_t cut = kMessageBytes;
      while (cut > 0 && (static_cast<unsigned char>(error[cut]) & 0xC0) == 0x80) --cut;  // (not inside a UTF-8 character)
      error = error.substr(0, cut) + "… (cut: " + std::to_string(error.size()) + " bytes in all)";
    }
    // The memory limit shows up as a failed allocation in the student's code.
    if (error.find("std::bad_alloc") != std::string::npos)
      throw ProbeFailure("your code ran out of its " + std::to_string(setup_.limits.memory_mb) + " MB (" + error + ")");
    throw ProbeFailure("your code stopped the run: " + error, false, true);
  }
  return reply;
}

}  // namespace motus::grade
