#include "motus/plugin/plugin_set.hpp"

#include <dlfcn.h>
#include <elf.h>
#include <link.h>
#include <signal.h>
#include <ucontext.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <cctype>
#include <exception>
#include <filesystem>
#include <fstream>

#include "motus/integrate/integrator_catalog.hpp"

namespace motus {

namespace {

// Whether a shared library is whole, read before dlopen maps it: a file cut short (a copy that
// did not finish) is mapped past its end, and the first read there is SIGBUS, which ended motus
// (exit 135, "crashed the process while it was being loaded"). The ELF header, its program
// headers and every segment to be loaded, and the section headers, must lie inside the file.
// "" when it is whole; otherwise what is wrong. (A file that is not ELF at all is dlopen's to name.)
std::string cut_short(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  Elf64_Ehdr header{};
  if (!in.read(reinterpret_cast<char*>(&header), sizeof header)) return "";
  if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64) return "";
  std::error_code error;
  const auto size = static_cast<std::uint64_t>(std::filesystem::file_size(path, error));
  if (error) return "";
  auto inside = [size](std::uint64_t offset, std::uint64_t length) { return offset <= size && length <= size - offset; };
  const char* cut = "cut short (a copy that did not finish?): ";
  if (header.e_phentsize != sizeof(Elf64_Phdr) ||
      !inside(header.e_phoff, std::uint64_t{header.e_phnum} * sizeof(Elf64_Phdr)))
    return std::string(cut) + "its program headers lie past its end";
  if (header.e_shnum > 0 && !inside(header.e_shoff, std::uint64_t{header.e_shnum} * header.e_shentsize))
    return std::string(cut) + "its section headers lie past its end";
  in.seekg(static_cast<std::streamoff>(header.e_phoff));
  for (int i = 0; i < header.e_phnum; ++i) {
    Elf64_Phdr segment{};
    if (!in.read(reinterpret_cast<char*>(&segment), sizeof segment)) return std::string(cut) + "its program headers are cut off";
    if (segment.p_type == PT_LOAD && !inside(segment.p_offset, segment.p_filesz))
      return std::string(cut) + "a segment it loads lies past its end";
  }
  return "";
}

// A plug-in's or its integrator's name: it is printed in tables and headers and typed in
// --integrator and --engines lists, so letters, digits, '_', '-' and '.' only, and short.
bool plain_name(const std::string& name) {
  if (name.empty() || name.size() > 40) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

PluginSet::~PluginSet() = default;  // the libraries stay loaded: their code may be on the stack of a dying run

void PluginSet::load(const std::string& file) {
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  // (a loop of links, a name too long, "p.so/": what the system says, not "no such file")
  if (error && error != std::errc::no_such_file_or_directory)
    throw PluginError(file + ": --plugin: " + error.message() + " (a plug-in is a shared library, FILE.so)");
  if (!std::filesystem::exists(status))
    throw PluginError(file + ": --plugin: no such file (a plug-in is a shared library, FILE.so)");
  if (!std::filesystem::is_regular_file(status))
    throw PluginError(file + ": --plugin: not a regular file (a plug-in is a shared library, FILE.so)");
  // A path without a slash would make dlopen search the library path instead of this file.
  const std::string path = file.find('/') == std::string::npos ? "./" + file : file;
  if (const std::string why = cut_short(path); !why.empty()) throw PluginError(file + ": --plugin: " + why);
  // A global's constructor that throws does so inside dlopen, which glibc declares noexcept: the
  // exception then ended in std::terminate, or went on to motus's own handlers (exit 1, the
  // plug-in not named) once this function had a cleanup around the call. The loader's state after
  // such an unwind is not to be trusted, so it always ends in std::terminate: report_crashes_
  // while_loading's one line, and abort. (Called through a pointer without noexcept, so that the
  // handler below is kept.)
  void* (*volatile open_library)(const char*, int) = dlopen;
  void* handle = nullptr;
  try {
    handle = open_library(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  } catch (...) {
    std::terminate();
  }
  if (!handle) throw PluginError(file + ": --plugin: not a plug-in motus can load: " + dlerror());
  using Entry = const PluginEntry* (*)();
  auto entry_point = reinterpret_cast<Entry>(dlsym(handle, kPluginEntryPoint));
  if (!entry_point)
    throw PluginError(file + ": --plugin: not a motus plug-in: it has no entry point " + kPluginEntryPoint +
                      " (build it with MOTUS_PLUGIN from motus/student/plugin.hpp)");
  const PluginEntry* entry = entry_point();
  if (!entry) throw PluginError(file + ": --plugin: its entry point " + kPluginEntryPoint + " returned nothing");
  if (entry->abi_version != kPluginAbiVersion)
    throw PluginError(file + ": --plugin: built for plug-in interface " + std::to_string(entry->abi_version) +
                      ", and this motus has " + std::to_string(kPluginAbiVersion) +
                      "; rebuild the plug-in against this motus");
  LoadedPlugin loaded;
  loaded.file = file;
  loaded.entry = entry;
  loaded.name = entry->name ? entry->name : "";
  loaded.description = entry->description ? entry->description : "";
  // One line of text where list and compare print it: control characters (a line break, a
  // terminal's escape) become spaces, and a page of it is cut.
  for (char& c : loaded.description)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  if (loaded.description.size() > 200) loaded.description = loaded.description.substr(0, 197) + "...";
  // (A name is shown only once it is known to be plain: one with a line break or a terminal's
  // escape codes in it would break the one-line message.)
  if (!plain_name(loaded.name))
    throw PluginError(file + ": --plugin: its name must be 1 to 40 letters, digits, '_', '-' or '.' (it prefixes "
                      "its integrators and names its column in compare)");
  for (const char* engine : {"motus", "box2d", "bullet", "odeint"})
    if (lower(loaded.name) == engine)
      throw PluginError(file + ": --plugin: its name \"" + loaded.name + "\" is a built-in engine's (" + engine + ")");
  for (const auto& other : plugins_)
    if (other.name == loaded.name)
      throw PluginError(file + ": --plugin: its name \"" + loaded.name + "\" clashes with " + other.file +
                        "; give each plug-in its own name");
  for (int i = 0; i < entry->integrator_count; ++i) {
    const ExternalIntegrator& integrator = entry->integrators[i];
    const std::string own = integrator.name ? integrator.name : "";
    if (!plain_name(own))
      throw PluginError(file + ": --plugin: integrator " + std::to_string(i) +
                        "'s name must be 1 to 40 letters, digits, '_', '-' or '.' (it is typed in --integrators lists)");
    if (integrator.kind < kExternalFirstOrder || integrator.kind > kExternalPositionVerlet)
      throw PluginError(file + ": --plugin: integrator \"" + own + "\" is of an unknown kind " +
                        std::to_string(integrator.kind));
    const std::string full = loaded.name + ":" + own;
    if (integrator_from_name(full))
      throw PluginError(file + ": --plugin: integrator \"" + full + "\" clashes with a built-in");
    if (std::find(loaded.integrator_names.begin(), loaded.integrator_names.end(), full) !=
        loaded.integrator_names.end())
      throw PluginError(file + ": --plugin: brings the integrator \"" + full + "\" twice");
    loaded.integrator_names.push_back(full);
  }
  for (const auto& other : plugins_) {
    if (entry->collisions && other.entry->collisions)
      throw PluginError(file + ": --plugin: brings a collision response, and so does " + other.file +
                        "; load only one of them");
    if (entry->constraints && other.entry->constraints)
      throw PluginError(file + ": --plugin: brings a constraint projection, and so does " + other.file +
                        "; load only one of them");
  }
  plugins_.push_back(std::move(loaded));
  handles_.push_back(handle);
}

std::optional<Method> PluginSet::integrator(const std::string& name) const {
  for (const auto& p : plugins_)
    for (int i = 0; i < p.entry->integrator_count; ++i)
      if (p.integrator_names[static_cast<size_t>(i)] == name) return Method(p.entry->integrators[i], name);
  return std::nullopt;
}

std::vector<Method> PluginSet::integrators() const {
  std::vector<Method> all;
  for (const auto& p : plugins_)
    for (int i = 0; i < p.entry->integrator_count; ++i)
      all.emplace_back(p.entry->integrators[i], p.integrator_names[static_cast<size_t>(i)]);
  return all;
}

ExternalParts PluginSet::parts() const {
  ExternalParts parts;
  for (const auto& p : plugins_) {
    if (p.entry->collisions) parts.collisions = p.entry->collisions;
    if (p.entry->constraints) parts.constraints = p.entry->constraints;
  }
  return parts;
}

std::string PluginSet::parts_owner() const {
  for (const auto& p : plugins_)
    if (p.entry->collisions || p.entry->constraints) return p.name;
  return plugins_.empty() ? "" : plugins_.front().name;
}

// ---- Crash reports -------------------------------------------------------------------------
namespace {

// Prepared while loading, read by the signal handler (which may only use what is
// async-signal-safe: no allocation, write(2) only).
struct CodeRange {
  std::uintptr_t begin = 0, end = 0;
  char line[512] = {};  // "motus: the plug-in FILE (NAME) crashed the process"
};
constexpr int kMaxPlugins = 16;
CodeRange g_ranges[kMaxPlugins];
int g_range_count = 0;
char g_loaded_line[1024] = {};  // when the crash was not in a plug-in's code

const char* signal_name(int signal) {
  switch (signal) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT";
    default: return "a signal";
  }
}

void write_all(const char* text) {
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= static_cast<size_t>(n);
  }
}

// Whether a fault at `address` with the stack pointer at `sp` is the stack running out: a call or
// a frame's locals written just below the stack pointer, into the guard page past the stack's end.
// (A student's endless recursion read as a bare "SIGSEGV", like a null pointer's, whose address is
// far from the stack.)
bool stack_overflow(std::uintptr_t address, std::uintptr_t sp) {
  constexpr std::uintptr_t kBelow = 1 << 20, kAbove = 1 << 12;  // (a frame of up to 1 MB of locals)
  return sp != 0 && address + kBelow >= sp && address <= sp + kAbove;
}

void on_crash(int signal, siginfo_t* info, void* context) {
  std::uintptr_t pc = 0, sp = 0;
#if defined(__x86_64__)
  pc = static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.gregs[REG_RIP]);
  sp = static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.gregs[REG_RSP]);
#elif defined(__aarch64__)
  pc = static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.pc);
  sp = static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.sp);
#else
  (void)context;
#endif
  const char* line = g_loaded_line;
  for (int i = 0; i < g_range_count; ++i)
    if (pc >= g_ranges[i].begin && pc < g_ranges[i].end) line = g_ranges[i].line;
  write_all(line);
  write_all(" (");
  write_all(signal_name(signal));
  if (signal == SIGSEGV && info && stack_overflow(reinterpret_cast<std::uintptr_t>(info->si_addr), sp))
    write_all(": the stack overflowed, as endless or too deep recursion does");
  write_all(")\n");
  ::signal(signal, SIG_DFL);  // and die of it, as the process would have
  ::raise(signal);
}

struct RangeSearch {
  const void* symbol;
  std::uintptr_t begin = 0, end = 0;
};

int find_range(dl_phdr_info* info, size_t, void* data) {
  auto* search = static_cast<RangeSearch*>(data);
  std::uintptr_t begin = ~std::uintptr_t{0}, end = 0;
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const auto& ph = info->dlpi_phdr[i];
    if (ph.p_type != PT_LOAD) continue;
    begin = std::min<std::uintptr_t>(begin, info->dlpi_addr + ph.p_vaddr);
    end = std::max<std::uintptr_t>(end, info->dlpi_addr + ph.p_vaddr + ph.p_memsz);
  }
  const auto at = reinterpret_cast<std::uintptr_t>(search->symbol);
  if (at >= begin && at < end) {
    search->begin = begin;
    search->end = end;
    return 1;
  }
  return 0;
}

void copy_line(char* out, size_t size, const std::string& text) {
  std::snprintf(out, size, "%s", text.c_str());
}

void install_crash_handlers() {
  struct sigaction action {};
  action.sa_sigaction = on_crash;
  action.sa_flags = SA_SIGINFO | SA_ONSTACK;
  sigemptyset(&action.sa_mask);
  // An alternate stack, so that a stack overflow in the plug-in can still be reported.
  static std::vector<char> alternate(1 << 16);
  stack_t stack{};
  stack.ss_sp = alternate.data();
  stack.ss_size = alternate.size();
  sigaltstack(&stack, nullptr);
  for (int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) sigaction(signal, &action, nullptr);
}

char g_threw_line[600] = {};  // "motus: the plug-in FILE threw ... while it was being loaded\n"
std::terminate_handler g_previous_terminate = nullptr;

}  // namespace

void report_crashes_while_loading(const std::string& file) {
  g_range_count = 0;
  copy_line(g_loaded_line, sizeof g_loaded_line, "motus: the plug-in " + file + " crashed the process while it was being loaded");
  copy_line(g_threw_line, sizeof g_threw_line,
            "motus: the plug-in " + file + " threw an exception while it was being loaded (in a global's constructor?)\n");
  install_crash_handlers();
  // An exception out of a global's constructor ends in std::terminate: one line, not libstdc++'s two.
  const std::terminate_handler previous = std::set_terminate([] {
    write_all(g_threw_line);
    ::signal(SIGABRT, SIG_DFL);
    std::abort();
  });
  if (!g_previous_terminate) g_previous_terminate = previous;
}

void report_plugin_crashes(const PluginSet& plugins) {
  if (plugins.empty()) return;
  std::string loaded;
  g_range_count = 0;
  for (const auto& p : plugins.plugins()) {
    loaded += (loaded.empty() ? "" : ", ") + p.file;
    if (g_range_count == kMaxPlugins) continue;
    RangeSearch search{p.entry};
    dl_iterate_phdr(find_range, &search);
    CodeRange& range = g_ranges[g_range_count++];
    range.begin = search.begin;
    range.end = search.end;
    copy_line(range.line, sizeof range.line,
              "motus: the plug-in " + p.file + " (" + p.name + ") crashed the process in its own code");
  }
  copy_line(g_loaded_line, sizeof g_loaded_line, "motus: the process crashed while running with the plug-in" +
                                                      std::string(plugins.plugins().size() > 1 ? "s " : " ") + loaded);
  if (g_previous_terminate) std::set_terminate(g_previous_terminate), g_previous_terminate = nullptr;
  install_crash_handlers();
}

}  // namespace motus
