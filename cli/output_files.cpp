#include "output_files.hpp"

#include <fcntl.h>
#include <stdio.h>  // renameat2, RENAME_NOREPLACE
#include <stdlib.h>  // mkdtemp
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <ctime>
#include <fstream>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "motus/plot/write_failure.hpp"

namespace fs = std::filesystem;

namespace motus::cli {

std::string safe_file_name(const std::string& name) {
  std::string safe;
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '-' || c == '_';
    safe += keep ? c : '_';
  }
  while (!safe.empty() && (safe.front() == '.' || safe.front() == '_')) safe.erase(safe.begin());
  if (safe.size() > 64) safe.resize(64);
  while (!safe.empty() && (safe.back() == '.' || safe.back() == '_')) safe.pop_back();
  return safe.empty() ? "scene" : safe;
}

fs::path without_trailing_separators(const std::string& path) {
  fs::path target(path);
  while (!target.has_filename() && target.has_relative_path()) target = target.parent_path();
  return target;
}

std::string default_run_folder(const std::string& kind, const std::string& scene_name) {
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  return fmt::format("runs/{}-{}-{}", kind, safe_file_name(scene_name), stamp);  // (a scene's name is not a path)
}

std::vector<std::string> folders_not_there_yet(const std::string& folder) {
  std::vector<std::string> missing;
  std::error_code ignored;
  for (fs::path above = folder; !above.empty() && !fs::exists(fs::symlink_status(above, ignored));
       above = above.parent_path()) {
    missing.push_back(above.string());
    if (above == above.parent_path()) break;
  }
  return missing;
}

std::string why_not_created(const std::string& folder, const std::error_code& error) {
  // A link to nothing on the way ("runs" left pointing at a folder since removed): create_directories
  // says only "File exists", which sends the reader looking for a file that is not there.
  std::error_code ignored;
  for (fs::path above = folder; !above.empty(); above = above.parent_path()) {
    if (fs::is_symlink(fs::symlink_status(above, ignored)) && !fs::exists(fs::status(above, ignored)))
      return above.string() + " is a link to " + fs::read_symlink(above, ignored).string() + ", which does not exist";
    if (above == above.parent_path()) break;
  }
  return error.message();
}

namespace {
std::string said_as_final(std::string message, const std::string& partial, const std::string& final) {
  if (partial.empty()) return message;
  for (size_t at = message.find(partial); at != std::string::npos; at = message.find(partial, at + final.size()))
    message.replace(at, partial.size(), final);
  return message;
}

struct SaidAsFinal {
  std::mutex lock;  // (grade --batch writes its results from several threads)
  std::vector<std::pair<std::string, std::string>> names;  // partial, final
};
SaidAsFinal& said_as_final_names() {
  static SaidAsFinal names;
  return names;
}
}  // namespace

void say_as_final(const std::string& partial, const std::string& final) {
  SaidAsFinal& said = said_as_final_names();
  const std::lock_guard<std::mutex> hold(said.lock);
  for (auto& [from, to] : said.names)
    if (from == partial) {
      to = final;
      return;
    }
  said.names.emplace_back(partial, final);
}

void say_as_it_is(const std::string& partial) {
  SaidAsFinal& said = said_as_final_names();
  const std::lock_guard<std::mutex> hold(said.lock);
  std::erase_if(said.names, [&](const auto& name) { return name.first == partial; });
}

std::string named_as_final(std::string message) {
  SaidAsFinal& said = said_as_final_names();
  const std::lock_guard<std::mutex> hold(said.lock);
  // (the latest first: a file's own temporary folder inside a run's, "r.partial-X/.f.partial-Y/f")
  for (auto name = said.names.rbegin(); name != said.names.rend(); ++name)
    message = said_as_final(std::move(message), name->first, name->second);
  return message;
}

void remove_if_empty(const std::vector<std::string>& folders) {
  for (const auto& folder : folders) {
    // ("x/./y" and "a/b/../c" list x/. and a/b/..: no folders of their own, and no reason to stop)
    if (const fs::path name = fs::path(folder).filename(); name == "." || name == "..") continue;
    std::error_code error;
    fs::remove(folder, error);  // (one already gone counts as removed: render's --out, taken with its frames)
    if (error) return;          // not empty: it and the folders above it stay
  }
}

PartialFolder::PartialFolder(const std::string& final_path, bool numbered)
    : final_(without_trailing_separators(final_path).string()), numbered_(numbered) {
  const fs::path target(final_);
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code error;
  made_parents_ = folders_not_there_yet(parent.string());  // (made now; removed again if the work never gets there)
  fs::create_directories(parent, error);
  if (error) throw InputError(final_ + ": cannot be created (" + why_not_created(parent.string(), error) + ")");
  std::string pattern = (parent / partial_name_for(target.filename().string())).string();
  if (!::mkdtemp(pattern.data())) {
    const std::string why = std::strerror(errno);
    remove_if_empty(made_parents_);
    throw InputError(final_ + ": cannot be created (" + why + ")");
  }
  // As a folder made by create_directories would be (mkdtemp makes 0700): 0777 less the umask.
  const mode_t umask = ::umask(0);
  ::umask(umask);
  ::chmod(pattern.c_str(), 0777 & ~umask);
  partial_ = pattern;
  say_as_final(partial_, final_);
}

PartialFolder::~PartialFolder() {
  if (done_) return;
  std::error_code ignored;
  fs::remove_all(partial_, ignored);
  remove_if_empty(made_parents_);
}

namespace {
// Renames `from` to `to` unless something is at `to` already (then false; the check and the rename
// are one step, RENAME_NOREPLACE, so nothing that appears in between is replaced). A file system
// without that flag gets a hard link and an unlink instead, which refuse the same way (files only).
bool rename_without_replacing(const std::string& from, const std::string& to) {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return true;
  if (errno == EEXIST) return false;
  if (errno == EINVAL || errno == ENOSYS) {
    if (::link(from.c_str(), to.c_str()) == 0) {
      ::unlink(from.c_str());
      return true;
    }
    if (errno == EEXIST) return false;
  }
  throw std::runtime_error(to + ": could not be written (" + std::strerror(errno) + ")");
}
}  // namespace

const std::string& PartialFolder::complete() {
  const std::string name = final_;
  for (int n = 2; !rename_without_replacing(partial_, final_); ++n) {
    if (!numbered_ || n > 100000) {
      done_ = true;  // (kept where the message says it is)
      say_as_it_is(partial_);
      throw std::runtime_error(final_ + ": appeared while the report was written; it is in " + partial_);
    }
    final_ = name + "-" + std::to_string(n);
  }
  done_ = true;
  say_as_final(partial_, final_);  // (numbered: where it is now)
  return final_;
}

PartialFile::PartialFile(const std::string& final_path) : final_(final_path) {
  std::string pattern = partial_folder_pattern_for(final_path);
  if (!::mkdtemp(pattern.data()))
    throw InputError(final_ + ": cannot be written (" + std::string(std::strerror(errno)) + ")");
  folder_ = pattern;
  file_ = (fs::path(folder_) / fs::path(final_path).filename()).string();
  say_as_final(file_, final_);
}

PartialFile::~PartialFile() {
  if (done_) return;
  std::error_code ignored;
  fs::remove_all(folder_, ignored);
}

void PartialFile::complete(bool overwrite) {
  std::error_code error;
  if (overwrite) {
    // The file replaced keeps its permissions: a user's 0600 file came back 0644, readable by all.
    // (A link in its place is replaced, not written through: what it points to may be outside the
    // folder the user gave.)
    struct stat replaced {};
    if (::lstat(final_.c_str(), &replaced) == 0 && S_ISREG(replaced.st_mode))
      ::chmod(file_.c_str(), replaced.st_mode & 07777);
    fs::rename(file_, final_, error);
    if (error) throw std::runtime_error(final_ + ": could not be written (" + error.message() + ")");
  } else if (!rename_without_replacing(file_, final_)) {
    done_ = true;  // (kept: it is the only copy of the work)
    say_as_it_is(file_);
    throw std::runtime_error(final_ + ": appeared while it was written, and is left as it is (no --overwrite); what was "
                                      "written is in " + file_);
  }
  done_ = true;
  fs::remove(folder_, error);
}

bool written_in_place(const std::string& path) {
  std::error_code ignored;
  const auto status = fs::status(path, ignored);
  return fs::exists(status) && !fs::is_regular_file(status);
}

void write_whole_file(const std::string& path, const std::string& text, bool overwrite) {
  std::optional<PartialFile> partial;
  if (!written_in_place(path)) partial.emplace(path);
  {
    std::ofstream out(partial ? partial->path() : path, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot be written (" + std::strerror(errno) + ")");
    errno = 0;
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(plot::write_failure(path));
  }
  if (partial) partial->complete(overwrite);
}

fs::file_status looked_at(const std::string& path, const std::string& option) {
  std::error_code error;
  const auto status = fs::status(path, error);
  if (error && error != std::errc::no_such_file_or_directory && error != std::errc::not_a_directory)
    throw InputError(path + ": " + (option.empty() ? "" : option + ": ") + error.message());
  return status;
}

bool output_exists(const std::string& path) {
  // (Nothing there, or a part of the way that is a file, is for the folder's making to report.)
  auto absent = [](const std::error_code& e) {
    return !e || e == std::errc::no_such_file_or_directory || e == std::errc::not_a_directory;
  };
  std::error_code error;
  // ("f/" is f: a file or a dangling link there is f's, though "f/" itself names nothing)
  const auto status = fs::symlink_status(without_trailing_separators(path), error);  // (fails through a loop of links on the way, too)
  if (!absent(error)) throw InputError(path + ": " + error.message());
  return fs::exists(status);
}

void check_can_write(const std::string& path, bool overwrite) {
  std::error_code error;
  const auto status = fs::status(path, error);
  // (A FIFO or a device is no file the user wrote: it is written as it is, below — also through a
  // link to one, as /dev/stderr is when it is a terminal or a pipe.)
  const auto link_status = fs::symlink_status(path, error);
  const bool link = fs::is_symlink(link_status);
  const bool to_a_device = link && fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status);
  // A link to an open descriptor (/dev/stderr → /proc/self/fd/2) whose file is a regular one: with
  // --overwrite the link itself was replaced (as root, /dev/stdout became a file of rows).
  if (link && !to_a_device) {
    const fs::path target = fs::read_symlink(path, error);
    if (!error && target.string().starts_with("/proc/"))
      throw InputError(path + ": is a link to an open file (" + target.string() +
                       "); motus writes no file through a link: for standard output, use -");
  }
  if ((fs::is_regular_file(link_status) || link) && !to_a_device && !overwrite)
    throw InputError(path + ": already exists; choose another name or pass --overwrite");
  if (fs::is_directory(status)) throw InputError(path + ": is a folder, not a file");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) {
    // (a loop of links or a name too long on the way: what the system says, not "does not exist")
    const auto folder = fs::status(parent, error);
    if (error && error != std::errc::no_such_file_or_directory && error != std::errc::not_a_directory)
      throw InputError(path + ": " + error.message());
    if (!fs::is_directory(folder))
      throw InputError(path + ": folder " + parent.string() + (fs::exists(folder) ? " is a file" : " does not exist"));
  }
  // A file beside it, made and removed at once: a folder that takes no new file (/proc, a
  // read-only disk) or a name too long is bad input now, not a failure after the work. (A FIFO
  // or a device is written as it is, and needs no new file.)
  if (fs::exists(status) && !fs::is_regular_file(status)) return;
  const fs::path folder = parent.empty() ? fs::path(".") : parent;
  // (The file itself is written in a folder with a longer name, a PartialFile's, then moved.)
  const long name_max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
  const std::string name = fs::path(path).filename().string();
  if (name_max > 0 && (static_cast<long>(name.size()) > name_max ||
                       static_cast<long>(partial_name_for(name).size()) > name_max))
    throw InputError(path + ": the file name is too long (at most " + std::to_string(std::min<long>(name_max, NAME_MAX)) +
                     " bytes here)");
  const std::string probe = (folder / (".motus-probe-" + std::to_string(::getpid()))).string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0 && errno != EEXIST) throw InputError(path + ": cannot be written there (" + std::strerror(errno) + ")");
  if (fd >= 0) ::close(fd), ::unlink(probe.c_str());
}

// (A legal name of 240–255 bytes was refused as "File name too long", or failed after its work.)
std::string partial_name_for(const std::string& name) {
  const std::string named = "." + name + ".partial-XXXXXX";
  return named.size() <= NAME_MAX ? named : std::string(".partial-XXXXXX");
}

std::string partial_folder_pattern_for(const std::string& path) {
  const fs::path target(path);
  return (target.parent_path() / partial_name_for(target.filename().string())).string();
}

void check_can_replace(const std::string& path, bool overwrite) {
  check_can_write(path, overwrite);
  std::error_code error;
  const auto status = fs::symlink_status(path, error);
  if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_symlink(status))
    throw InputError(path + ": is not a regular file (a device or a FIFO); --overwrite replaces regular files only");
}


}  // namespace motus::cli
