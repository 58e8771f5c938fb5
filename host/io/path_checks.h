// path_checks.h — what a render may do with the names a user types, checked before it starts
// (README "Nothing lost"): no output may be an input (an overwritten scene or reference is work
// lost), a checkpoint overwrites only a checkpoint, and a file to be read must be a regular file
// (a FIFO would block the read for ever).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace fen {

// The path with every symbolic link in the part that exists followed and "." and ".." removed,
// made absolute: two names of one file compare equal (hard links: see sameFile).
std::string resolvedPath(const std::string& path);

// Whether a and b name one existing file (same device and inode), or resolve to the same path.
bool sameFile(const std::string& a, const std::string& b);

// Throws fen::Error when `output` (written by `option`) is the same file as one of `inputs`
// ({what, path}: "the scene", "--reference", ...).
void refuseOverwritingInputs(const std::string& output, const std::string& option,
                             const std::vector<std::pair<std::string, std::string>>& inputs);

// Throws fen::Error unless `path` names an existing regular file (after links); `option` names it.
void requireRegularFile(const std::string& path, const std::string& option);

}  // namespace fen
