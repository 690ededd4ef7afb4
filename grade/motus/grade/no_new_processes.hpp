#pragma once
// The probe server (`motus serve`) forbids itself new processes before it loads a student's
// plug-in: the sandbox's memory limit (RLIMIT_AS) holds one process, and a submission that
// forked could hold it once per child (64 children of 512 MB). Threads stay allowed: they share
// the process's memory, and so its limit.
#include <string>

namespace motus::grade {

// From here on this process (and its threads) cannot start a process or a program: fork, vfork and
// clone without CLONE_VM fail with EPERM, execve (so posix_spawn's and system's child) with EPERM,
// clone3 with ENOSYS (glibc then makes its threads with clone). A seccomp filter: it cannot be lifted, and it holds
// for every thread made after it. Throws std::runtime_error when the kernel refuses the filter
// or this machine's architecture has no filter here (x86-64 and AArch64 do).
void forbid_new_processes();

}  // namespace motus::grade
