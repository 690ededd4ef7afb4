#include "interrupt.hpp"

#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>

#include "motus/process/run_program.hpp"

namespace motus::cli {
namespace {

// (Atomic, not only volatile: grade's workers read it from their threads. Lock-free, so that the
// handler may set it.)
std::atomic<int> g_interrupted{0};
static_assert(std::atomic<int>::is_always_lock_free);

// What one step may take before motus reaches a safe point: a step of an O(N²) force over 10⁵
// bodies, or a peer's set-up of 10⁵ bodies, takes minutes, and an interrupt must not wait for it.
constexpr unsigned kGraceSeconds = 30;
// After this long without a safe point motus says that it waits for one, and how not to (a
// student's plug-in in an endless loop has none: the first Ctrl-C seemed to do nothing).
constexpr unsigned kNoticeSeconds = 2;
volatile sig_atomic_t g_noticed = 0;
// What else stop_now calls (on_stop_at_once).
std::atomic<void (*)() noexcept> g_also[4] = {};
static_assert(std::atomic<void (*)() noexcept>::is_always_lock_free);  // (read in stop_now, from a handler)

// What else on_interrupt calls (on_interrupt_also).
std::atomic<void (*)() noexcept> g_on_interrupt[4] = {};

// Only async-signal-safe calls here: write, kill and _exit.
[[noreturn]] void stop_now(const char* why) {
  process::kill_running_programs();  // (an ffmpeg motus started went on writing after it)
  for (auto& also : g_also)
    if (const auto f = also.load()) f();
  const char* line = "motus: interrupted; ";
  for (const char* text : {line, why, " (what was being written may be left under its temporary .NAME.partial-XXXXXX name)\n"}) {
    size_t length = 0;
    while (text[length]) ++length;
    if (::write(STDERR_FILENO, text, length) < 0) break;
  }
  ::_exit(kExitInterrupted);
}

// A second interrupt this soon after the first is the same one, delivered twice: `timeout` signals
// motus and then its own process group, which holds motus too (and a terminal's Ctrl-C reaches
// every process of the group at once). Counted as a second one, it stopped motus at once and left
// its partial folder behind; a person's second Ctrl-C comes a good deal later than this.
constexpr long long kSameInterruptNanoseconds = 50'000'000;
std::atomic<long long> g_first_interrupt{0};
static_assert(std::atomic<long long>::is_always_lock_free);

long long monotonic_nanoseconds() {  // (clock_gettime is async-signal-safe)
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<long long>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

void on_interrupt(int) {
  const int saved = errno;
  const long long now = monotonic_nanoseconds();
  if (g_interrupted) {
    if (now - g_first_interrupt.load() >= kSameInterruptNanoseconds) stop_now("stopped at once, at the second interrupt");
    errno = saved;
    return;
  }
  g_first_interrupt = now;
  g_interrupted = 1;
  // The programs motus waits for (gnuplot, ffmpeg, zip) are ended, not waited for: a gnuplot that
  // caught the same Ctrl-C and hung kept motus waiting out the 30 s below, and its partial report
  // was left. SIGTERM now, SIGKILL after a short grace (run_program).
  process::stop_running_programs();
  for (auto& also : g_on_interrupt)
    if (const auto f = also.load()) f();
  ::alarm(kNoticeSeconds);  // no safe point yet: on_alarm says so, then waits out the grace
  errno = saved;
}

void on_alarm(int) {
  const int saved = errno;  // (the write below must not change what the interrupted code reads)
  if (!g_noticed) {
    g_noticed = 1;
    const char notice[] = "\nmotus: interrupted; stopping at the next safe point (Ctrl-C again stops at once)\n";
    if (::write(STDERR_FILENO, notice, sizeof notice - 1) < 0) {
      // (nothing to do: the grace still runs)
    }
    ::alarm(kGraceSeconds - kNoticeSeconds);
    errno = saved;
    return;
  }
  stop_now("no safe point came within 30 s, so stopped there");
}

}  // namespace

void catch_interrupts() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a wait for a child returns at once
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);  // (a terminal closed, an ssh dropped: motus died leaving its partial files)
  action.sa_handler = on_alarm;
  sigaction(SIGALRM, &action, nullptr);
  // A reader that went away (motus ... | head) makes a write fail with EPIPE, which the writes'
  // checks report (exit 1, one line), instead of a signal that ends motus without a word.
  ::signal(SIGPIPE, SIG_IGN);
}

void on_stop_at_once(void (*also)() noexcept) {
  for (auto& slot : g_also) {
    void (*empty)() noexcept = nullptr;
    if (!also || slot.load() == also || slot.compare_exchange_strong(empty, also)) return;
  }
}

void on_interrupt_also(void (*also)() noexcept) {
  for (auto& slot : g_on_interrupt) {
    void (*empty)() noexcept = nullptr;
    if (!also || slot.load() == also || slot.compare_exchange_strong(empty, also)) return;
  }
}

bool interrupted() { return g_interrupted != 0; }

void stop_if_interrupted() {
  if (g_interrupted) throw Interrupted();
}

}  // namespace motus::cli
