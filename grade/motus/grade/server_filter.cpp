#include "motus/grade/server_filter.hpp"

#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/syscall.h>

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace motus::grade {
namespace {

#if defined(__x86_64__)
constexpr unsigned kArchitecture = AUDIT_ARCH_X86_64;
#elif defined(__aarch64__)
constexpr unsigned kArchitecture = AUDIT_ARCH_AARCH64;
#else
constexpr unsigned kArchitecture = 0;  // none: install_server_filter refuses
#endif

// Classic BPF, one instruction at a time, read top to bottom: the filter looks at the system
// call's architecture, number and (for clone) its flags, and answers allow, an error, or kill.
sock_filter load(unsigned offset) { return BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offset); }
sock_filter answer(unsigned what) { return BPF_STMT(BPF_RET | BPF_K, what); }
// If the accumulator equals `value`, skip `then_skip` instructions, else `else_skip`.
sock_filter jump_if_equal(unsigned value, unsigned char then_skip, unsigned char else_skip) {
  return BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, value, then_skip, else_skip);
}

}  // namespace

void install_server_filter() {
  if (kArchitecture == 0)
    throw std::runtime_error(
        "no seccomp filter for this machine's architecture: the probe server cannot hold the student's code to its "
        "limits");
  constexpr unsigned kArch = offsetof(seccomp_data, arch), kNumber = offsetof(seccomp_data, nr);
  // (The flags are clone's first argument; its low 32 bits come first on these little-endian machines.)
  constexpr unsigned kFlags = offsetof(seccomp_data, args);
  const sock_filter refuse = answer(SECCOMP_RET_ERRNO | EPERM);
  std::vector<sock_filter> filter = {
      // A system call of another architecture (32-bit int 0x80 on x86-64) would bypass the numbers below.
      load(kArch), jump_if_equal(kArchitecture, 1, 0), answer(SECCOMP_RET_KILL_PROCESS),
      load(kNumber),
  };
#if defined(__x86_64__)
  // x32's numbers (bit 30 set) name the same calls under other numbers: none is needed.
  filter.push_back(BPF_JUMP(BPF_JMP | BPF_JGE | BPF_K, 0x40000000u, 0, 1));
  filter.push_back(answer(SECCOMP_RET_KILL_PROCESS));
#endif
  // Programs and processes, and memory outside the address space: refused.
  const std::vector<unsigned> refused = {
#ifdef __NR_fork
      __NR_fork,
#endif
#ifdef __NR_vfork
      __NR_vfork,
#endif
      __NR_execve, __NR_execveat, __NR_memfd_create, __NR_shmget, __NR_msgget,
      // (a new IPC namespace allows 32,000 sets of 32,000 semaphores: 750 of them held 1.5 GB)
      __NR_semget,
      // (a socket's queue holds up to twice net.core.wmem_max, 8 MB here, outside the address space)
      __NR_socket, __NR_socketpair,
      // (a page spliced into a pipe keeps its whole huge page: 700 of them held 1.4 GB)
      __NR_vmsplice, __NR_splice, __NR_tee,
      // Namespaces and mounts: in a namespace of its own the code could mount a tmpfs of any size (the
      // sandbox forbids new user namespaces too), and a descriptor table of its own per thread
      // (unshare(CLONE_FILES)) would multiply the descriptors' limit.
      __NR_unshare, __NR_setns, __NR_mount, __NR_umount2, __NR_pivot_root, __NR_open_tree, __NR_move_mount,
      __NR_fsopen, __NR_fsconfig, __NR_fsmount, __NR_fspick,
      // io_uring: its operations are made by the kernel, out of this filter's sight (IORING_OP_SOCKET
      // made 248 sockets after socket was refused, and their queues held 1 GB past the memory limit).
      __NR_io_uring_setup, __NR_io_uring_enter, __NR_io_uring_register};
  for (const unsigned number : refused) {
    filter.push_back(jump_if_equal(number, 0, 1));
    filter.push_back(refuse);
  }
  // clone3 keeps its flags in memory, out of a filter's reach: "not implemented", on which glibc
  // falls back to clone for its threads.
  filter.push_back(jump_if_equal(__NR_clone3, 0, 1));
  filter.push_back(answer(SECCOMP_RET_ERRNO | ENOSYS));
  // clone: a thread allowed — CLONE_THREAD with CLONE_VM and CLONE_FILES, all three: the same
  // memory, so the same memory limit, and the same descriptor table, so the same descriptors'
  // limit; anything else refused — fork's copy of the memory, a process that shares it, and a
  // thread with a descriptor table of its own (20 such processes held 5,000 descriptors against the
  // 256; one thread without CLONE_FILES held 504).
  // (Under the sanitizers a task that shares the memory and the descriptors is allowed too:
  // LeakSanitizer's tracer is one, made with CLONE_VM | CLONE_FS | CLONE_FILES | CLONE_UNTRACED.)
#ifdef MOTUS_SANITIZE
  constexpr unsigned kAllowedWith = CLONE_VM | CLONE_FILES;
#else
  constexpr unsigned kAllowedWith = CLONE_THREAD | CLONE_VM | CLONE_FILES;
#endif
  filter.push_back(jump_if_equal(__NR_clone, 0, 4));
  filter.push_back(load(kFlags));
  filter.push_back(BPF_STMT(BPF_ALU | BPF_AND | BPF_K, kAllowedWith));
  filter.push_back(jump_if_equal(kAllowedWith, 1, 0));
  filter.push_back(refuse);
  filter.push_back(answer(SECCOMP_RET_ALLOW));
  const sock_fprog program{static_cast<unsigned short>(filter.size()), filter.data()};
  // (No new privileges: a filter may then be installed without CAP_SYS_ADMIN. The sandbox set it already.)
  if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0 || ::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &program) != 0)
    throw std::runtime_error(std::string("the kernel refused the probe server's seccomp filter: ") +
                             std::strerror(errno));
}

}  // namespace motus::grade
