// Hostile submissions to `motus grade` (docs/grading.md, "The sandbox"): code that loops,
// crashes, aborts, throws, eats memory, forks without end, floods its output, writes outside
// its folder, reads the hidden tests and the solution, or reaches for the network — and a
// submission that does not compile and an empty one. Each ends within its limits with a valid
// result; only the tests that call the hostile function lose, with a message naming what
// happened; nothing is left running and nothing outside the sandbox changes.
// It runs alone (RUN_SERIAL): "nothing left running" looks at every sandbox user's processes.
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "grade_harness.hpp"

namespace {

using namespace motus_test;
using nlohmann::json;

// ---------------------------------------------------------------------------------------------------
// Hostile submissions: the integrators' solution with euler_step doing harm first

struct Hostile {
  std::string name, includes, body;
  std::string message;  // what the affected tests' output says ("" : they pass)
  std::string run_message = "";  // and what euler.table's says (a run's: the others are steps and runs of their own)
};

// Code that writes `line` once, at its first call, to the server's answers' descriptor (3: its
// standard output kept apart, the lowest free when serve starts), ahead of the server's own reply.
std::string forging(const std::string& line_expression) {
  return "static bool forged = false; if (!forged) { forged = true; const std::string line = " + line_expression +
         "; for (size_t at = 0; at < line.size();) { const ssize_t n = ::write(3, line.data() + at, line.size() - at); "
         "if (n <= 0) break; at += size_t(n); } }";
}

TEST(Grade, HostileSubmissionsEndWithinTheirLimitsAndHarmNothing) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path marker = dir / "written-by-the-student";
  const std::string solution = (fs::path(kAssignments) / "integrators/solution/integrators.cpp").string();
  const std::string hidden_file = (fs::path(kAssignments) / "integrators/hidden/hidden.json").string();
  // A port this process listens on, for the attempt to reach the network.
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::listen(listener, 4), 0);
  socklen_t length = sizeof address;
  ::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length);
  const int port = ntohs(address.sin_port);

  const std::vector<Hostile> cases = {
      {"loop", "", "for (volatile long i = 0;; i = i + 1) {}", "timed out after 2 s of CPU"},
      {"segfault", "", "*static_cast<volatile int*>(nullptr) = 1;", "killed by SIGSEGV"},
      {"abort", "#include <cstdlib>\n", "std::abort();", "killed by SIGABRT"},
      {"exception", "#include <stdexcept>\n", "throw std::out_of_range(\"deliberately\");",
       "threw std::out_of_range: deliberately"},
      // Bytes that are not UTF-8 (what an editor that saves Latin-1 gives) in what it prints.
      {"not-utf-8", "#include <cstdio>\n#include <cstdlib>\n", "std::fputs(\"caf\\xe9 \\xff\\xfe\\n\", stderr); std::abort();",
       "killed by SIGABRT"},
      {"memory", "#include <vector>\n",
       "std::vector<double> big(size_t(10) << 27); big[12345] = 1; if (big[12345] > 2) return;", "ran out of its 512 MB"},
      {"fork-bomb", "#include <unistd.h>\n", "for (;;) ::fork();", "timed out after 2 s of CPU"},
      // Children that each hold memory: each under the 512 MB, together past it (20 of 300 MB used 6 GB
      // of the machine and scored full marks). Now fork and programs are refused: the tests pass on
      // the solution's own numbers, and a fork or a program that did start fails them.
      {"fork-memory", "#include <cstdlib>\n#include <cstring>\n#include <stdexcept>\n#include <unistd.h>\n",
       "static bool tried = false; if (!tried) { tried = true; for (int c = 0; c < 4; ++c) { const pid_t child = ::fork(); "
       "if (child == 0) { void* held = std::malloc(size_t(300) << 20); if (held) std::memset(held, 1, size_t(300) << 20); "
       "::pause(); ::_exit(0); } if (child > 0) throw std::runtime_error(\"FORKED\"); } "
       "if (std::system(\"exit 0\") == 0) throw std::runtime_error(\"RAN A PROGRAM\"); }",
       ""},
      // Memory outside the address space, which the limit does not see: memfd files and System V
      // shared memory filled and unmapped (12 + 12 of 60 MB: 1.4 GB held), a socket's queue, and
      // descriptors past the sandbox's 256 (the machine allows 20,000). All refused now.
      {"memory-elsewhere",
       "#include <sched.h>\n#include <sys/ipc.h>\n#include <sys/mman.h>\n#include <sys/shm.h>\n#include <sys/socket.h>\n"
       "#include <unistd.h>\n#include <cstring>\n#include <stdexcept>\n#include <string>\n",
       "static bool tried = false; if (!tried) { tried = true; const size_t chunk = size_t(60) << 20; size_t held = 0; "
       "for (int i = 0; i < 12; ++i) { const int fd = ::memfd_create(\"held\", 0); if (fd < 0 || ::ftruncate(fd, chunk) != 0) break; "
       "void* p = ::mmap(nullptr, chunk, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0); if (p == MAP_FAILED) break; "
       "std::memset(p, 1, chunk); ::munmap(p, chunk); held += chunk; } "
       "for (int i = 0; i < 12; ++i) { const int id = ::shmget(IPC_PRIVATE, chunk, IPC_CREAT | 0600); if (id < 0) break; "
       "void* p = ::shmat(id, nullptr, 0); if (p == reinterpret_cast<void*>(-1)) break; std::memset(p, 1, chunk); ::shmdt(p); "
       "held += chunk; } "
       "if (held > 0) throw std::runtime_error(\"HELD \" + std::to_string(held >> 20) + \" MB OUTSIDE ITS ADDRESS SPACE\"); "
       "int pair[2]; if (::socketpair(AF_UNIX, SOCK_STREAM, 0, pair) == 0) throw std::runtime_error(\"MADE A SOCKET PAIR\"); "
       // (closed again: the server's own work after it needs a few, as the sanitizers' reports do)
       "int opened[300]; int count = 0; while (count < 300 && (opened[count] = ::dup(0)) >= 0) ++count; "
       "for (int i = 0; i < count; ++i) ::close(opened[i]); "
       "if (count == 300) throw std::runtime_error(\"OPENED 300 DESCRIPTORS\"); "
       // A thread without CLONE_FILES has a descriptor table of its own, and 256 more descriptors
       // (one held 504 against the 256): refused too.
       "static char stack[1 << 16]; if (::clone(+[](void*) -> int { for (;;) ::pause(); }, stack + sizeof stack, "
       "CLONE_VM | CLONE_SIGHAND | CLONE_THREAD, nullptr) >= 0) throw std::runtime_error(\"MADE A THREAD WITH DESCRIPTORS OF ITS OWN\"); }",
       ""},
      // Kernel memory by other ways (a red-team pass found each holding 1.1 to 1.5 GB): a user and mount
      // namespace of its own, to mount a tmpfs of any size; System V semaphores; a page spliced into a
      // pipe (it keeps its huge page); a million empty files in /tmp (a tmpfs limits bytes, not files).
      {"kernel-memory",
       "#include <fcntl.h>\n#include <sched.h>\n#include <sys/ipc.h>\n#include <sys/sem.h>\n#include <sys/syscall.h>\n"
       "#include <sys/uio.h>\n#include <unistd.h>\n#include <stdexcept>\n",
       "static bool tried = false; if (!tried) { tried = true; "
       "if (::unshare(CLONE_NEWUSER | CLONE_NEWNS) == 0) throw std::runtime_error(\"MADE A NAMESPACE\"); "
       "if (::semget(IPC_PRIVATE, 32000, IPC_CREAT | 0600) >= 0) throw std::runtime_error(\"MADE SEMAPHORES\"); "
       "int ends[2]; static char page[4096]; iovec piece{page, sizeof page}; "
       "if (::pipe(ends) == 0 && ::vmsplice(ends[1], &piece, 1, SPLICE_F_NONBLOCK) > 0) throw std::runtime_error(\"SPLICED\"); "
       "if (::open(\"/tmp/one-of-a-million\", O_CREAT | O_WRONLY, 0600) >= 0) throw std::runtime_error(\"MADE A FILE\"); "
       // io_uring's operations are the kernel's, out of the filter's sight: its IORING_OP_SOCKET made
       // 248 sockets after socket() was refused, and their queues held 1 GB.
       "char params[512] = {}; if (::syscall(SYS_io_uring_setup, 4, params) >= 0) throw std::runtime_error(\"MADE AN IO_URING\"); }",
       ""},
      {"flood", "#include <iostream>\n#include <string>\n",
       // 256 MB at the first call of each test: drained, it costs a fraction of the 2 s, and the
       // tests pass. (A gigabyte on every call passed or timed out, by the machine's load.)
       "static bool flooded = false; if (!flooded) { flooded = true; static const std::string junk(1 << 20, 'x'); "
       "for (int i = 0; i < 256; ++i) std::cout << junk; }",
       ""},
      {"write-outside", "#include <fstream>\n", "std::ofstream(\"" + marker.string() + "\") << \"escaped\";", ""},
      // 8 MB of message: cut, as output is (it went whole into results.json).
      {"huge-message", "#include <stdexcept>\n#include <string>\n", "throw std::runtime_error(std::string(8 << 20, 'A'));",
       "threw std::runtime_error: AAAA"},
      // At its exit (after its answers): 70 MB down every descriptor, the answers' too, then a wait
      // for ever. The grader stopped reading past 64 MB and then waited for it in waitpid, for ever.
      {"holds-on-at-exit", "#include <cstdlib>\n#include <string>\n#include <unistd.h>\n",
       "static const bool hooked = [] { std::atexit([] { static const std::string junk(1 << 20, 'x'); "
       "for (int fd = 1; fd < 10; ++fd) for (int i = 0; i < 70; ++i) if (::write(fd, junk.data(), junk.size()) < 0) break; "
       "for (;;) ::pause(); }); return true; }(); (void)hooked;",
       ""},
      // Replies the student's code writes over the server's (on its answers' descriptor), whose shape
      // is not the request's: no times for 100 states of one number each (read as they came, they
      // crashed the grader, SIGSEGV, and the whole batch with it), no "t" at all (nlohmann's
      // out_of_range: "motus grade could not finish", every test lost), a state of one number for
      // two, 10 states of 200,001 numbers (40 MB: one test's output held 9 MB of them), and more
      // values than the run can need. Each fails the tests it answers, and only them.
      {"reply-without-times", "#include <unistd.h>\n#include <string>\n",
       forging("[] { std::string l = \"{\\\"ok\\\":true,\\\"t\\\":[],\\\"y\\\":[[0]\"; "
               "for (int i = 1; i < 100; ++i) l += \",[0]\"; return l + \"]}\\n\"; }()"),
       "was malformed: ", "The run's reply was malformed: 0 times but 100 states"},
      // A line that is no JSON at all read as the server's death: "your code exited with status 0".
      {"reply-not-json", "#include <unistd.h>\n#include <string>\n", forging("std::string(\"hello\\n\")"),
       "was malformed: ", "The run's reply was malformed: not JSON (it began \"hello\")"},
      {"reply-without-keys", "#include <unistd.h>\n#include <string>\n", forging("std::string(\"{\\\"ok\\\":true}\\n\")"),
       "was malformed: ", "The run's reply was malformed: it has no \"t\" or no \"y\""},
      {"reply-of-short-states", "#include <unistd.h>\n#include <string>\n",
       forging("std::string(\"{\\\"ok\\\":true,\\\"t\\\":[0,1],\\\"y\\\":[[0],[0]]}\\n\")"),
       "was malformed: ", "The run's reply was malformed: y[0] is not 2 numbers (the scene's state)"},
      {"reply-too-long", "#include <unistd.h>\n#include <string>\n",
       forging("[] { std::string row = \"[1\"; for (int i = 0; i < 200000; ++i) row += \",1.2345678901234567\"; "
               "std::string l = \"{\\\"ok\\\":true,\\\"t\\\":[0,1,2,3,4,5,6,7,8,9],\\\"y\\\":[\" + row; "
               "for (int i = 0; i < 9; ++i) l += \",\" + row; return l + \"]}\\n\"; }()"),
       "was malformed: ", "The run's reply was malformed: longer than"},
      // Within the bytes a run of 5 steps may send (66 kB), 30,000 values: zeros, which a parsed
      // document holds in 16 bytes each (63 MB of them held 1.1 GB). Refused as it is parsed.
      {"reply-of-many-values", "#include <unistd.h>\n#include <string>\n",
       forging("[] { std::string l = \"{\\\"ok\\\":true,\\\"t\\\":[0],\\\"y\\\":[[1,0]],\\\"z\\\":[0\"; "
               "for (int i = 1; i < 30000; ++i) l += \",0\"; return l + \"]}\\n\"; }()"),
       "was malformed: ", "The run's reply was malformed: more than 4132 JSON values"},
      // /dev is a tmpfs of its own, unsized: writable, it held memory past every limit.
      {"write-dev", "#include <fstream>\n#include <stdexcept>\n",
       "for (const char* f : {\"/dev/filled\", \"/dev/shm/filled\"}) if (std::ofstream(f) << \"x\") "
       "throw std::runtime_error(\"WROTE TO /dev\");",
       ""},
      {"read-hidden", "#include <fstream>\n#include <stdexcept>\n",
       "for (const char* f : {\"" + hidden_file + "\", \"" + solution +
           "\"}) if (std::ifstream(f)) throw std::runtime_error(\"READ THE ANSWERS\");",
       ""},
      {"network", "#include <sys/socket.h>\n#include <netinet/in.h>\n#include <stdexcept>\n",
       "{ int fd = ::socket(AF_INET, SOCK_STREAM, 0); sockaddr_in to{}; to.sin_family = AF_INET; to.sin_port = htons(" +
           std::to_string(port) +
           "); to.sin_addr.s_addr = htonl(0x7f000001); if (fd >= 0 && ::connect(fd, (sockaddr*)&to, sizeof to) == 0) "
           "throw std::runtime_error(\"CONNECTED\"); }",
       ""},
  };
  const std::string anchor = "void euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {\n";
  const std::string original = read_file(solution);
  ASSERT_NE(original.find(anchor), std::string::npos);
  for (const auto& c : cases) {
#ifdef MOTUS_SANITIZE  // no RLIMIT_AS under AddressSanitizer (docs/testing.md): a 10 GB allocation is ASan's to refuse
    if (c.name == "memory") continue;
#endif
    std::string source = original;
    source.replace(source.find(anchor), anchor.size(), anchor + "  " + c.body + "\n");
    fs::create_directories(dir / "batch" / c.name);
    write_file(dir / "batch" / c.name / "integrators.cpp", c.includes + source);
  }
  fs::create_directories(dir / "batch/does-not-compile");
  write_file(dir / "batch/does-not-compile/integrators.cpp", "#include \"integrators.hpp\"\nthis is not C++;\n" + original);
  // A function of the handout misspelt: the link names it (not a plug-in that fails every test).
  fs::create_directories(dir / "batch/misspelt");
  std::string misspelt = original;
  misspelt.replace(misspelt.find("void euler_step("), 16, "void euler_stpe(");
  write_file(dir / "batch/misspelt/integrators.cpp", misspelt);
  // A compiler error on a line with a Latin-1 comment: the compiler quotes bytes that are not UTF-8.
  fs::create_directories(dir / "batch/latin-1");
  write_file(dir / "batch/latin-1/integrators.cpp",
             "#include \"integrators.hpp\"\nint broken = \"r\xe9sum\xe9\"; // r\xe9sum\xe9\n" + original);
  fs::create_directories(dir / "batch/empty");

  const auto r = run_motus(dir, {"grade", "integrators", "--batch", (dir / "batch").string(), "--jobs", "2",
                                 "--time-limit", "2", "--out", (dir / "results").string()});
  ::close(listener);
  ASSERT_EQ(r.status, 0) << r.err;
  // (21 submissions, 2 at a time, each test at most 2 s: a grader that hung would meet ctest's TIMEOUT.)

  double public_max = 0;
  const auto defs = definitions("integrators");
  const auto p = points("integrators");
  for (const auto& [name, pts] : p)
    if (defs.count(name) && read_file(fs::path(kAssignments) / "integrators/tests/public.json").find("\"" + name + "\"") != std::string::npos)
      public_max += pts;
  const std::set<std::string> euler_tests = {"euler.table", "euler.order", "euler.step-time"};
  for (const auto& c : cases) {
    if (!fs::exists(dir / "results" / (c.name + ".json")) && c.name == "memory") continue;  // (skipped above)
    const json result = read_json(dir / "results" / (c.name + ".json"));
    expect_valid_gradescope(result);
    const std::set<std::string> lost = failed(result);
    if (c.message.empty()) {
      EXPECT_TRUE(lost.empty()) << c.name << ": " << ::testing::PrintToString(lost);
    } else {
      EXPECT_EQ(lost, euler_tests) << c.name;  // only the tests that call euler_step; the others are graded
      for (const auto& name : euler_tests) {
        const json* t = test_named(result, name);
        ASSERT_NE(t, nullptr);
        EXPECT_NE((*t)["output"].get<std::string>().find(c.message), std::string::npos) << c.name << ": " << (*t)["output"];
      }
      if (!c.run_message.empty()) {
        const json* t = test_named(result, "euler.table");
        ASSERT_NE(t, nullptr);
        EXPECT_NE((*t)["output"].get<std::string>().find(c.run_message), std::string::npos) << c.name << ": " << (*t)["output"];
      }
    }
    double euler_points = 0;
    for (const auto& name : euler_tests) euler_points += p.at(name);
    EXPECT_GE(result["score"].get<double>(), public_max - euler_points) << c.name;
    // Output is kept up to its cap.
    for (const auto& t : result["tests"]) EXPECT_LT(t["output"].get<std::string>().size(), 8000u) << c.name;
  }
  EXPECT_FALSE(fs::exists(marker)) << "a file written by the submission appeared outside its sandbox";
  EXPECT_TRUE(sandbox_processes_left().empty()) << ::testing::PrintToString(sandbox_processes_left());

  const json broken = read_json(dir / "results/does-not-compile.json");
  expect_valid_gradescope(broken);
  EXPECT_EQ(broken["score"].get<double>(), 0);
  const json* build = test_named(broken, "build");
  ASSERT_NE(build, nullptr);
  const std::string errors = (*build)["output"].get<std::string>();
  EXPECT_NE(errors.find("error:"), std::string::npos) << errors;  // the compiler's own words
  EXPECT_LE(count_lines(errors), 45) << errors;                   // cut to a readable length

  const json misspelt_result = read_json(dir / "results/misspelt.json");
  expect_valid_gradescope(misspelt_result);
  const json* misspelt_build = test_named(misspelt_result, "build");
  ASSERT_NE(misspelt_build, nullptr);
  EXPECT_EQ((*misspelt_build)["status"], "failed");
  EXPECT_NE((*misspelt_build)["output"].get<std::string>().find("undefined reference to `student::euler_step("),
            std::string::npos) << (*misspelt_build)["output"];

  // Graded like any submission that does not compile, the bytes that are not UTF-8 shown as U+FFFD.
  const json latin = read_json(dir / "results/latin-1.json");
  expect_valid_gradescope(latin);
  const json* latin_build = test_named(latin, "build");
  ASSERT_NE(latin_build, nullptr);
  EXPECT_EQ((*latin_build)["status"], "failed");
  EXPECT_NE((*latin_build)["output"].get<std::string>().find("error:"), std::string::npos);
  EXPECT_NE((*latin_build)["output"].get<std::string>().find("\xef\xbf\xbd"), std::string::npos) << (*latin_build)["output"];

  const json empty = read_json(dir / "results/empty.json");
  expect_valid_gradescope(empty);
  EXPECT_EQ(empty["score"].get<double>(), 0);
  const json* files = test_named(empty, "files");
  ASSERT_NE(files, nullptr);
  EXPECT_EQ((*files)["status"], "failed");
  EXPECT_NE((*files)["output"].get<std::string>().find("integrators.cpp: missing"), std::string::npos);
}

TEST(Grade, NoExpectedValueReachesTheStudentsCode) {
  // A submission that reads everything the grader sends its process (a pipe put in front of
  // standard input when the plug-in is loaded, before the server reads a line). The Lorenz
  // scene of the hidden tests has reference states, which rk4.lorenz-order judges the run
  // against: they must not be among what it saw. (And it must have seen the requests, the runs'
  // scenes among them: else it proves nothing. A `step` test calls rk4_step with no scene.)
  NEEDS_SANDBOX();
  TempDir dir;
  const std::string anchor = "void rk4_step(const FirstOrderSystem& f, double t, double h, VectorInOut y) {\n";
  // (The scene travels as a JSON string in the request: its keys' quotes escaped.)
  const std::string checks = R"(  std::lock_guard<std::mutex> lock(seen_lock);
  if (seen.find(R"-("op")-") == std::string::npos) throw std::runtime_error("SAW NOTHING");
  if (seen.find(R"-("run")-") != std::string::npos && seen.find(R"-(\"dt\")-") == std::string::npos)
    throw std::runtime_error("SAW NO SCENE");
  if (seen.find(R"-(\"reference\")-") != std::string::npos) throw std::runtime_error("SAW THE REFERENCE");
)";
  const std::string spy = R"(#include <unistd.h>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
namespace {
std::string seen;
std::mutex seen_lock;
struct Spy {
  Spy() {
    int p[2];
    if (::pipe(p) != 0) return;
    const int real = ::dup(0);
    ::dup2(p[0], 0);
    ::close(p[0]);
    std::thread([real, to = p[1]] {
      char buffer[4096];
      for (ssize_t n; (n = ::read(real, buffer, sizeof buffer)) > 0;) {
        { std::lock_guard<std::mutex> lock(seen_lock); seen.append(buffer, static_cast<size_t>(n)); }
        if (::write(to, buffer, static_cast<size_t>(n)) != n) break;
      }
      ::close(to);
    }).detach();
  }
} spy;
}  // namespace
)";
  const fs::path submission = integrators_solution_with(dir, "spy", anchor, anchor + checks, spy);
  ASSERT_FALSE(submission.empty());
  const auto r = run_motus(dir, {"grade", "integrators", submission.string(), "--hidden", hidden("integrators"),
                                 "--time-limit", "5", "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  ASSERT_NE(test_named(result, "rk4.lorenz-order"), nullptr);
  EXPECT_TRUE(failed(result).empty()) << result.dump(2);
}

// Ctrl-C while the student's code runs (here a loop that never ends, under a 600 s limit) or
// compiles ends the grading at once: exit 130, and nothing that looks like results. The sandbox
// has a process group of its own, which the terminal's Ctrl-C never reaches, and motus used to
// wait for the test's limit (or the compiler) before it looked at the interrupt; a batch aborted
// ("terminate called without an active exception") and left its folder half filled.
// A submission that stops reading its input: at its first call it shrinks its input pipe to one
// page and has a thread hold stdin's lock, so that its server answers the first request and
// never reads another. The grader's next request (a scene of 16 KB: more than the pipe holds)
// used to wait in write() for ever — past the test's limit, and past Ctrl-C. It times out as
// any other test does, and grading goes on: at the wall clock's backstop (2 × 2 s + 5 s), with
// a message that says it was waiting, not computing (it used none of its CPU).
TEST(Grade, ASubmissionThatStopsReadingItsInputTimesOut) {
  NEEDS_SANDBOX();
  TempDir dir;
  json test = definitions("integrators").at("euler.order");  // four runs, one server
  ASSERT_EQ(test["scene"], "oscillator");
  test.erase("scene");
  test["scene_file"] = "scenes/long_oscillator.json";
  const fs::path assignment = integrators_with_tests(dir, "long", json::array({test}));
  json scene = read_json(fs::path(kScenes) / "oscillator.json");
  scene.erase("$schema");
  scene["description"] = std::string(16 << 10, 'x');
  fs::create_directories(assignment / "tests/scenes");
  write_file(assignment / "tests/scenes/long_oscillator.json", scene.dump(1));
  const fs::path submission = solution_with_euler_step_starting(
      dir, "stops-reading",
      "static bool first = true; if (first) { first = false; ::fcntl(0, F_SETPIPE_SZ, 4096); "
      "std::thread([] { ::flockfile(stdin); for (;;) ::pause(); }).detach(); ::usleep(100000); }",
      "#include <fcntl.h>\n#include <unistd.h>\n#include <cstdio>\n#include <thread>\n");
  ASSERT_FALSE(submission.empty());
  MotusFiles files;
  files.err = (dir / "err.txt").string();
  files.folder = dir.path().string();
  const pid_t pid = start_motus_with({"grade", assignment.string(), submission.string(), "--time-limit", "2", "--results",
                                      (dir / "results.json").string()},
                                     files);
  ASSERT_GT(pid, 0);
  int raw = 0;
  ASSERT_TRUE(ended_within(pid, 120, raw)) << "grading hung: " << read_file(dir / "err.txt");
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << raw << ": " << read_file(dir / "err.txt");
  const json result = read_json(dir / "results.json");  // (kept: test_named points into it)
  expect_valid_gradescope(result);
  const json* t = test_named(result, "euler.order");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ((*t)["status"], "failed");
  EXPECT_NE((*t)["output"].get<std::string>().find(
                "timed out after 9 s waiting, not computing (blocked or asleep, it did not use its 2 s of CPU) during"),
            std::string::npos)
      << (*t)["output"];
  EXPECT_TRUE(sandbox_processes_left().empty()) << ::testing::PrintToString(sandbox_processes_left());
}

// Without a sandbox the student's code can reach the folder its plug-in was built in: one that
// replaced its own plug-in with a link (here to /etc/hostname) had the grader copy what the link
// leads to into --plugin-out. The grader now refuses to copy anything but the file it built.
TEST(Grade, ASubmissionThatReplacesItsOwnPluginGetsNoCopyOfWhatItPointsAt) {
  TempDir dir;
  const fs::path submission = solution_with_euler_step_starting(
      dir, "replaces-itself",
      "static bool done = false; if (!done) { done = true; std::ifstream maps(\"/proc/self/maps\"); "
      "for (std::string line; std::getline(maps, line);) { const auto at = line.find('/'); "
      "if (at != std::string::npos && line.find(\"student.so\") != std::string::npos) { "
      "const std::string so = line.substr(at); std::filesystem::remove(so); "
      "std::filesystem::create_symlink(\"/etc/hostname\", so); break; } } }",
      "#include <filesystem>\n#include <fstream>\n#include <string>\n");
  ASSERT_FALSE(submission.empty());
  const auto r = run_motus(dir, {"grade", "integrators", submission.string(), "--no-sandbox", "--results",
                                 (dir / "results.json").string(), "--plugin-out", (dir / "plugin.so").string()});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("the built plug-in is no longer a file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "plugin.so"));
}

TEST(Grade, CtrlCEndsTheGradingWhileTheStudentsCodeRuns) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path submission = solution_with_euler_step_starting(dir, "batch/loops", "for (volatile long i = 0;; i = i + 1) {}");
  // (Two that loop: a correct second submission graded within the 3 s below on a fast machine,
  // and the batch then rightly kept its graded folder for it.)
  ASSERT_FALSE(solution_with_euler_step_starting(dir, "batch/loops_too", "for (volatile long i = 0;; i = i + 1) {}").empty());
  auto interrupt = [&](const std::vector<std::string>& args) {
    MotusFiles files;
    files.err = (dir / "err.txt").string();
    files.folder = dir.path().string();
    const pid_t pid = start_motus_with(args, files);
    if (pid <= 0) return -1;
    if (!wait_until_catching(pid, SIGINT)) {
      int ignored = 0;
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &ignored, 0);
      return -1;
    }
    ::sleep(3);  // (the compiler or the first test underway: either way motus waits for a sandbox)
    ::kill(pid, SIGINT);
    int raw = 0;
    return ended_within(pid, 60, raw) ? raw : -2;  // (60 s at most, against the 600 s it would wait)
  };
  const int one = interrupt({"grade", "integrators", submission.string(), "--time-limit", "600", "--results",
                             (dir / "results.json").string()});
  EXPECT_TRUE(WIFEXITED(one) && WEXITSTATUS(one) == 130) << one << " (-2: not ended in 60 s): " << read_file(dir / "err.txt");
  // (Not by the 30 s of grace that motus gives a step without a safe point: that was the old way out.)
  EXPECT_EQ(read_file(dir / "err.txt").find("no safe point came within 30 s"), std::string::npos) << read_file(dir / "err.txt");
  EXPECT_FALSE(fs::exists(dir / "results.json"));
  const int batch = interrupt({"grade", "integrators", "--batch", (dir / "batch").string(), "--jobs", "2", "--time-limit",
                               "600", "--out", (dir / "graded").string()});
  EXPECT_TRUE(WIFEXITED(batch) && WEXITSTATUS(batch) == 130) << batch << ": " << read_file(dir / "err.txt");
  EXPECT_EQ(read_file(dir / "err.txt").find("no safe point came within 30 s"), std::string::npos) << read_file(dir / "err.txt");
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find("graded"), std::string::npos) << e.path();  // nor .graded.partial-…
}

// A batch interrupted after some submissions were graded keeps their results, as grading.md says
// (each took its seconds of grading): the folder is there without a scores.csv. It was removed
// whole, with the message "nothing half-written was left behind".
TEST(Grade, CtrlCInABatchKeepsTheSubmissionsGradedSoFar) {
  NEEDS_SANDBOX();
  TempDir dir;
  copy_solution(dir, "integrators", "batch/a_correct");
  solution_with_euler_step_starting(dir, "batch/b_loops", "for (volatile long i = 0;; i = i + 1) {}");
  MotusFiles files;
  files.err = (dir / "err.txt").string();
  files.folder = dir.path().string();
  const pid_t pid = start_motus_with({"grade", "integrators", "--batch", (dir / "batch").string(), "--time-limit", "600",
                                      "--out", (dir / "graded").string()},
                                     files);
  ASSERT_GT(pid, 0);
  // Interrupted once a_correct's results are written (then b_loops is being graded, for 600 s).
  auto a_graded = [&] {
    for (const auto& e : fs::directory_iterator(dir.path()))
      if (e.path().filename().string().starts_with(".graded.partial-") && fs::exists(e.path() / "a_correct.json")) return true;
    return false;
  };
  for (int tenth = 0; tenth < 1200 && !a_graded(); ++tenth) ::usleep(100'000);
  const bool graded = a_graded();
  ::kill(pid, SIGINT);
  int raw = 0;
  ASSERT_TRUE(ended_within(pid, 60, raw)) << read_file(dir / "err.txt");
  ASSERT_TRUE(graded) << "a_correct was not graded within 120 s: " << read_file(dir / "err.txt");
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 130) << raw << ": " << read_file(dir / "err.txt");
  ASSERT_TRUE(fs::exists(dir / "graded/a_correct.json")) << read_file(dir / "err.txt");
  EXPECT_EQ(json::parse(read_file(dir / "graded/a_correct.json"))["score"], 25);  // (the solution's full marks: its public tests' 25 points)
  EXPECT_FALSE(fs::exists(dir / "graded/b_loops.json"));
  EXPECT_FALSE(fs::exists(dir / "graded/scores.csv"));
  EXPECT_NE(read_file(dir / "err.txt").find("the 1 submission graded so far has its results in"), std::string::npos)
      << read_file(dir / "err.txt");
}

}  // namespace
