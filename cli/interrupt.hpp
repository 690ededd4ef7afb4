#pragma once
// Ctrl-C (SIGINT), SIGTERM and SIGHUP: motus stops at the next safe point, removes what it was
// writing, and exits with status 130 — never a report folder that looks complete but is not.
#include <stdexcept>

namespace motus::cli {

// The exit status of an interrupted run.
constexpr int kExitInterrupted = 130;

class Interrupted : public std::runtime_error {
public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// From now on SIGINT, SIGTERM and SIGHUP set a flag, and end the programs motus waits for (gnuplot,
// ffmpeg, zip: SIGTERM, then SIGKILL after process::kTerminateGraceMs) rather than wait for them.
// A second one, or 30 s with no safe point after the first, ends motus at once (exit 130).
void catch_interrupts();
bool interrupted();
// Throws Interrupted once an interrupt has come.
void stop_if_interrupted();
// Also called when motus stops at once (a second interrupt), before it exits: an async-signal-safe
// function that ends what a loaded module started (its ffmpeg). Up to four.
void on_stop_at_once(void (*also)() noexcept);
// Also called at the first interrupt: an async-signal-safe function that ends the programs a loaded
// module is waiting for (its ffmpeg). Up to four.
void on_interrupt_also(void (*also)() noexcept);

}  // namespace motus::cli
