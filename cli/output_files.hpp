#pragma once
// Files and folders written whole or not at all (PartialFolder, PartialFile, write_whole_file), the
// checks before anything is written (check_can_write), and the names of outputs and of run folders.
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace motus::cli {

// A name (a scene's, say) made safe as one file name: letters, digits, '.', '-' and '_' are
// kept, anything else becomes '_', no leading dot, at most 64 characters; "scene" if nothing is
// left. A scene named "../victim" writes "victim", inside the folder it was given.
std::string safe_file_name(const std::string& name);

// The folder of a run the user gave no --out for: runs/KIND-SCENE-YYYYmmdd-HHMMSS (KIND: compare,
// precision, stress). Not made here: a PartialFolder made with `numbered` takes it, or the first of
// NAME-2, NAME-3, … free when the run is whole (two runs of a scene started in the same second
// both get a folder).
std::string default_run_folder(const std::string& kind, const std::string& scene_name);

// "out/" names the folder "out": its parent is the parent of out, not out itself (which
// parent_path() of "out/" would give, and a report would be made inside the folder it is to become).
std::filesystem::path without_trailing_separators(const std::string& path);

// The folders above a path that are not there yet (`folder` and its parents up to the first that
// exists), deepest first: the ones a create_directories(folder) will make, and that a run which fails
// or is stopped removes again (remove_if_empty) — an interrupted run said "nothing half-written was
// left behind" and left the empty folders of its --out's path.
std::vector<std::string> folders_not_there_yet(const std::string& folder);
// Why `folder` could not be made, for "cannot be created (...)": a link to nothing on its way named
// as such, or else `error`'s own words.
std::string why_not_created(const std::string& folder, const std::error_code& error);
// Removes each of `folders` (deepest first) while it is empty or already gone; stops at the first that
// is not (nothing with anything in it is ever removed).
void remove_if_empty(const std::vector<std::string>& folders);

// A message with every temporary folder or file this process has made (PartialFolder, PartialFile,
// render's folder) said as what it was to become: a failure removes the temporary one, and a
// message naming it named a path gone. main's one-line errors go through it, so that
// "a/.r.partial-Xb3/summary.json: could not be written" reads "a/r/summary.json: …". One that is
// kept (a name taken meanwhile: the message says where the work is) is said as it is.
void say_as_final(const std::string& partial, const std::string& final);
void say_as_it_is(const std::string& partial);
std::string named_as_final(std::string message);

// A folder written under a temporary name and renamed to `final_path` only when complete()
// is called; otherwise the destructor removes it and everything in it. Throws InputError
// when it cannot be made.
class PartialFolder {
public:
  // numbered: final_path is a default name (default_run_folder), and when it is taken the folder
  // goes to final_path-2, -3, … instead of failing.
  explicit PartialFolder(const std::string& final_path, bool numbered = false);
  ~PartialFolder();
  PartialFolder(const PartialFolder&) = delete;
  PartialFolder& operator=(const PartialFolder&) = delete;
  const std::string& path() const { return partial_; }
  // Where the folder is now. Throws std::runtime_error when the rename fails (e.g. a name the user
  // gave was taken meanwhile: the work is kept where the message says).
  const std::string& complete();

private:
  std::string final_, partial_;
  std::vector<std::string> made_parents_;  // the folders above it that it made, deepest first
  bool numbered_;
  bool done_ = false;
};

// A file written whole or not at all: written as NAME inside a new folder of its own beside it
// (.NAME.partial-XXXXXX, made by mkdtemp, so that nothing already there is truncated and no link
// is followed), and moved to `final_path` by complete(): over a file there only with
// `overwrite`; without it, a file that appeared there meanwhile is left as it is (an error that
// says where the work was kept). Otherwise the destructor removes the folder and the file.
// Throws InputError when the folder cannot be made.
class PartialFile {
public:
  explicit PartialFile(const std::string& final_path);
  ~PartialFile();
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;
  const std::string& path() const { return file_; }  // where to write it
  void complete(bool overwrite);                     // throws std::runtime_error naming final_path

private:
  std::string final_, folder_, file_;
  bool done_ = false;
};

// Refuses to overwrite an existing file unless asked to (nothing the user wrote is
// lost without being asked), and a folder even then. For a file written in place: a FIFO or a
// device (/dev/full) is written to as it is.
void check_can_write(const std::string& path, bool overwrite);
// Writes `text` to `path` whole or not at all (through a PartialFile), over a file there only with
// `overwrite`; a FIFO or a device is written as it is. Fails with one line naming the path.
void write_whole_file(const std::string& path, const std::string& text, bool overwrite);
// Whether `path` is written as it is rather than through a PartialFile: a FIFO or a device.
bool written_in_place(const std::string& path);
// The temporary name of a file or folder named `name`, with mkdtemp's XXXXXX: .NAME.partial-XXXXXX,
// or .partial-XXXXXX when that would be longer than a file name may be.
std::string partial_name_for(const std::string& name);
// The folder a PartialFile for `path` is written in: partial_name_for its name, beside it.
std::string partial_folder_pattern_for(const std::string& path);
// The same for a file written whole under another name and then renamed over `path`: the
// rename would put a regular file where a device or a FIFO was, so only a regular file (or a
// link, which the rename replaces and does not follow) may be overwritten.
void check_can_replace(const std::string& path, bool overwrite);

// What is at `path` (links followed), for an input the user named: a path that cannot be looked at
// (a loop of links, a name too long, a folder not to be entered) is bad input, one line naming it
// and `option` ("--batch"; "" for an argument), where std::filesystem's throwing calls made it
// "the run failed: filesystem error: status: …", exit 1. Nothing there is a status of not_found.
std::filesystem::file_status looked_at(const std::string& path, const std::string& option = "");

// Whether something is at `path`, a folder an output would go to. A path that cannot be looked
// at (a name too long, a loop of links, a folder not to be entered) is bad input naming it.
bool output_exists(const std::string& path);

}  // namespace motus::cli
