#pragma once
// What the probe server (`motus serve`) forbids itself before it loads a student's plug-in: the
// sandbox's memory limit (RLIMIT_AS) holds one process's address space, and code that held memory
// anywhere else would escape it — in forked children (20 of 300 MB held 6 GB of the machine), in
// memfd files or System V shared memory filled and unmapped again (40 of 60 MB held 2.4 GB), in
// semaphores, message queues, sockets' queues, pages spliced into pipes, or a tmpfs mounted in a
// namespace of its own. Threads stay allowed: they share the process's memory, and so its limit.
// (Pipes' buffers are bounded by the kernel per user; descriptors, locked memory and POSIX queues by
// the sandbox's rlimits. Page tables are not: 65,530 mappings, the kernel's most, can hold about
// 1 GB of them; only a memory cgroup would count them, and motus makes none.)
#include <string>

namespace motus::grade {

// From here on this process (and its threads) cannot start a process or a program, nor hold memory
// outside its address space: fork, vfork and a clone that is not a thread sharing the memory and
// the descriptors (CLONE_THREAD, CLONE_VM and CLONE_FILES, all three) fail with EPERM, execve (so
// posix_spawn's and system's child) with EPERM, clone3 with ENOSYS (glibc then makes its threads
// with clone); memfd_create, shmget, msgget, semget, socket, socketpair, vmsplice, splice, tee,
// unshare, setns, the mount calls and io_uring (setup, enter, register) with EPERM. A seccomp filter: it cannot be lifted, and it
// holds for every thread made after it. Throws std::runtime_error when the kernel refuses
// the filter or this machine's architecture has no filter here (x86-64 and AArch64 do).
void install_server_filter();

}  // namespace motus::grade
