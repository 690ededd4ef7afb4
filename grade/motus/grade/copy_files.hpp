#pragma once
// Copying files with the cause of a failure told as it is. std::filesystem::copy_file (libstdc++'s,
// through sendfile) reports any short copy as "Input/output error": a full disk (ENOSPC) or a
// file-size limit (EFBIG) read as a broken disk, and its message ("filesystem error: cannot copy:
// … [from] [to]") named both paths in brackets. These say "TO: could not be written (No space left
// on device)", as every other write of motus's does.
#include <string>

namespace motus::grade {

// `from` (a regular file, links followed) copied to `to`, which is replaced if it is there.
void copy_file_told(const std::string& from, const std::string& to);

// `from` copied to `to`: a file as copy_file_told does, a folder (made, with its parents) with
// everything in it, links followed, each file by copy_file_told.
void copy_tree_told(const std::string& from, const std::string& to);

}  // namespace motus::grade
