#include "motus/plugin/plugin_set.hpp"

#include <dlfcn.h>
#include <link.h>
#include <signal.h>
#include <ucontext.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>

#include "motus/integrator_name.hpp"

namespace motus {

PluginSet::~PluginSet() = default;  // the libraries stay loaded: their code may be on the stack of a dying run

void PluginSet::load(const std::string& file) {
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (!std::filesystem::exists(status))
    throw PluginError(file + ": --plugin: no such file (a plug-in is a shared library, FILE.so)");
  if (!std::filesystem::is_regular_file(status))
    throw PluginError(file + ": --plugin: not a regular file (a plug-in is a shared library, FILE.so)");
  // A path without a slash would make dlopen search the library path instead of this file.
  const std::string path = file.find('/') == std::string::npos ? "./" + file : file;
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
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
  if (loaded.name.empty() || loaded.name.find_first_of(":, \t") != std::string::npos)
    throw PluginError(file + ": --plugin: its name \"" + loaded.name +
                      "\" must be a word without ':', ',' or spaces (it prefixes its integrators)");
  if (loaded.name == "motus" || loaded.name == "box2d" || loaded.name == "bullet")
    throw PluginError(file + ": --plugin: its name \"" + loaded.name + "\" is a built-in engine's");
  for (const auto& other : plugins_)
    if (other.name == loaded.name)
      throw PluginError(file + ": --plugin: its name \"" + loaded.name + "\" clashes with " + other.file +
                        "; give each plug-in its own name");
  for (int i = 0; i < entry->integrator_count; ++i) {
    const ExternalIntegrator& integrator = entry->integrators[i];
    const std::string own = integrator.name ? integrator.name : "";
    if (own.empty()) throw PluginError(file + ": --plugin: integrator " + std::to_string(i) + " has no name");
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

void on_crash(int signal, siginfo_t*, void* context) {
  std::uintptr_t pc = 0;
#if defined(__x86_64__)
  pc = static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.gregs[REG_RIP]);
#elif defined(__aarch64__)
  pc = static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.pc);
#else
  (void)context;
#endif
  const char* line = g_loaded_line;
  for (int i = 0; i < g_range_count; ++i)
    if (pc >= g_ranges[i].begin && pc < g_ranges[i].end) line = g_ranges[i].line;
  write_all(line);
  write_all(" (");
  write_all(signal_name(signal));
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
