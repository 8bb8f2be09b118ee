// Output folders a user names (--out): created when missing, refused when the path is
// something else, locked while a command writes into them.
#pragma once

#include <string>

namespace markerbench {

// Creates `dir` and its parents. Throws ConfigError (exit 2) naming `dir` when it exists and
// is not a folder, std::runtime_error naming it with the system's reason when it cannot be
// created (no permission, a full disk).
void CreateOutputFolder(const std::string& dir);

// Creates `dir` for a command that fills a whole folder (render): an existing folder must be
// empty, or, with `overwrite`, hold a dataset markerbench wrote (dataset.json), which is then
// emptied; never a mix of two runs, and never the emptying of a folder of something else.
// ConfigError naming `dir` otherwise.
void CreateEmptyOutputFolder(const std::string& dir, bool overwrite);

// Creates `dir` as above and takes an advisory lock on it (DIR/markerbench.lock), held until
// the process ends: a second sweep or merge into `dir` is a ConfigError instead of
// interleaving its rows with this one's.
void LockOutputFolder(const std::string& dir);

}  // namespace markerbench
