// The probe server's seccomp filter (grade/motus/grade/server_filter.hpp), installed in a child of
// this test: what it refuses fails with the errno it names, and what a student's ordinary code
// uses (threads, std::async, memory) still works. The whole path — a hostile submission
// graded in the sandbox — is tests/test_grade_hostile.cpp's "fork-memory", "memory-elsewhere" and
// "kernel-memory".
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/ipc.h>
#include <sys/mman.h>
#include <sys/mount.h>
#include <sys/msg.h>
#include <sys/sem.h>
#include <sys/shm.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/uio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include "motus/grade/server_filter.hpp"

namespace {

// What the child found, one bit per check that went wrong.
enum Wrong : int {
  kForked = 1 << 0,
  kExecuted = 1 << 1,
  kMemfd = 1 << 2,
  kSharedMemory = 1 << 3,
  kMessageQueue = 1 << 4,
  kSocket = 1 << 5,
  kSystem = 1 << 6,
  kNoThread = 1 << 7,
  kNoAsync = 1 << 8,
  kNoMemory = 1 << 9,
  kNotInstalled = 1 << 10,
  kSemaphores = 1 << 11,
  kSpliced = 1 << 12,
  kNamespace = 1 << 13,
  kSharedMemoryProcess = 1 << 14,
  kIoUring = 1 << 15,
  kThreadOwnDescriptors = 1 << 16,
};

int child_of_clone(void*) { return 0; }

// A thread of clone's own that holds 4 descriptors of its own table, whose count it leaves in
// `arg` (an int that starts at -1); it waits, so that the descriptors stay held, until the test's
// process ends.
int thread_with_its_own_descriptors(void* arg) {
  int held = 0;
  while (held < 4 && ::dup(0) >= 0) ++held;
  __atomic_store_n(static_cast<int*>(arg), held, __ATOMIC_RELEASE);
  for (;;) ::pause();
}

int checks_after_the_filter() {
  try {
    motus::grade::install_server_filter();
  } catch (...) {
    return kNotInstalled;
  }
  int wrong = 0;
  auto refused = [](long result, int expected_errno) { return result == -1 && errno == expected_errno; };
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  if (!refused(child, EPERM)) wrong |= kForked;
  char* const argv[] = {const_cast<char*>("/bin/true"), nullptr};
  if (!refused(::execve("/bin/true", argv, nullptr), EPERM)) wrong |= kExecuted;
  if (!refused(::memfd_create("held", 0), EPERM)) wrong |= kMemfd;
  if (!refused(::shmget(IPC_PRIVATE, 1 << 20, IPC_CREAT | 0600), EPERM)) wrong |= kSharedMemory;
  if (!refused(::msgget(IPC_PRIVATE, IPC_CREAT | 0600), EPERM)) wrong |= kMessageQueue;
  int pair[2];
  if (!refused(::socket(AF_UNIX, SOCK_STREAM, 0), EPERM) || !refused(::socketpair(AF_UNIX, SOCK_STREAM, 0, pair), EPERM))
    wrong |= kSocket;
  if (std::system("exit 0") == 0) wrong |= kSystem;  // (its child cannot start the shell)
  if (!refused(::semget(IPC_PRIVATE, 16, IPC_CREAT | 0600), EPERM)) wrong |= kSemaphores;
  int ends[2];
  static char page[4096];
  iovec piece{page, sizeof page};
  if (::pipe(ends) != 0 || !refused(::vmsplice(ends[1], &piece, 1, SPLICE_F_NONBLOCK), EPERM)) wrong |= kSpliced;
  if (!refused(::unshare(CLONE_NEWUSER | CLONE_NEWNS), EPERM) || !refused(::unshare(CLONE_FILES), EPERM) ||
      !refused(::mount("none", "/tmp", "tmpfs", 0, "size=4g"), EPERM))
    wrong |= kNamespace;
#ifndef MOTUS_SANITIZE  // (there a task sharing the memory is allowed: LeakSanitizer's tracer is one)
  // A process that shares the memory but has its own descriptors: refused (a thread is not).
  static char stack[1 << 16];
  const int sharing = ::clone(child_of_clone, stack + sizeof stack, CLONE_VM | SIGCHLD, nullptr);
  if (!refused(sharing, EPERM)) wrong |= kSharedMemoryProcess;
  // A thread without CLONE_FILES: a descriptor table of its own, and a second 256 descriptors (one
  // held 504 against the sandbox's 256). Refused; with CLONE_FILES it is the thread std::thread makes.
  static char thread_stack[1 << 16];
  static int thread_held = -1;
  const int thread = ::clone(thread_with_its_own_descriptors, thread_stack + sizeof thread_stack,
                             CLONE_VM | CLONE_SIGHAND | CLONE_THREAD, &thread_held);
  if (!refused(thread, EPERM)) wrong |= kThreadOwnDescriptors;
#endif
  // io_uring: the kernel makes its operations (a socket, say) out of the filter's sight.
  char params[512] = {};  // (struct io_uring_params, with room: its size varies with the kernel's headers)
  if (!refused(::syscall(__NR_io_uring_setup, 4, params), EPERM)) wrong |= kIoUring;
  if (!refused(::syscall(__NR_io_uring_enter, 0, 0, 0, 0, nullptr, 0), EPERM) ||
      !refused(::syscall(__NR_io_uring_register, 0, 0, nullptr, 0), EPERM))
    wrong |= kIoUring;
  // What ordinary code does: threads, std::async, memory.
  int from_thread = 0;
  std::thread([&] { from_thread = 42; }).join();
  if (from_thread != 42) wrong |= kNoThread;
  if (std::async(std::launch::async, [] { return 7; }).get() != 7) wrong |= kNoAsync;
  std::vector<double> memory(size_t(16) << 20, 1.0);  // 128 MB
  if (memory[12345] != 1.0) wrong |= kNoMemory;
  return wrong;
}

TEST(ServerFilter, RefusesProcessesAndMemoryOutsideTheAddressSpaceAndKeepsThreads) {
  // (The bits come back through a pipe: an exit status keeps 8 of them, and every check from
  // kNoAsync on was lost in it.)
  int bits[2];
  ASSERT_EQ(::pipe(bits), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(bits[0]);
    const int found = checks_after_the_filter();
    ::_exit(::write(bits[1], &found, sizeof found) == static_cast<ssize_t>(sizeof found) ? 0 : 1);
  }
  ::close(bits[1]);
  int wrong = 0;
  const ssize_t got = ::read(bits[0], &wrong, sizeof wrong);
  ::close(bits[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  ASSERT_EQ(WEXITSTATUS(status), 0);
  ASSERT_EQ(got, static_cast<ssize_t>(sizeof wrong));
  EXPECT_EQ(wrong & kNotInstalled, 0) << "the kernel refused the filter";
  EXPECT_EQ(wrong & kForked, 0) << "fork was not refused with EPERM";
  EXPECT_EQ(wrong & kExecuted, 0) << "execve was not refused with EPERM";
  EXPECT_EQ(wrong & kMemfd, 0) << "memfd_create was not refused with EPERM";
  EXPECT_EQ(wrong & kSharedMemory, 0) << "shmget was not refused with EPERM";
  EXPECT_EQ(wrong & kMessageQueue, 0) << "msgget was not refused with EPERM";
  EXPECT_EQ(wrong & kSocket, 0) << "socket or socketpair was not refused with EPERM";
  EXPECT_EQ(wrong & kSystem, 0) << "system() ran a shell";
  EXPECT_EQ(wrong & kNoThread, 0) << "a std::thread did not run";
  EXPECT_EQ(wrong & kNoAsync, 0) << "std::async did not run";
  EXPECT_EQ(wrong & kNoMemory, 0) << "128 MB could not be allocated";
  EXPECT_EQ(wrong & kSemaphores, 0) << "semget was not refused with EPERM";
  EXPECT_EQ(wrong & kSpliced, 0) << "vmsplice was not refused with EPERM";
  EXPECT_EQ(wrong & kNamespace, 0) << "unshare or mount was not refused with EPERM";
  EXPECT_EQ(wrong & kSharedMemoryProcess, 0) << "clone(CLONE_VM) without CLONE_THREAD was not refused with EPERM";
  EXPECT_EQ(wrong & kThreadOwnDescriptors, 0) << "clone(CLONE_THREAD) without CLONE_FILES was not refused with EPERM";
  EXPECT_EQ(wrong & kIoUring, 0) << "io_uring_setup, io_uring_enter or io_uring_register was not refused with EPERM";
}

}  // namespace
