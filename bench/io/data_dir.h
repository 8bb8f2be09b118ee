// Where the program's data lives: the scenarios, marker files and plotting script. Found from
// the executable's own location, never from a path fixed at compile time, so that an
// installed binary works anywhere: PREFIX/bin/markerbench reads PREFIX/share/markerbench/, and
// the build tree's build/bench/markerbench reads build/share/markerbench/ (links into the
// source tree that CMake makes).
#pragma once

#include <string>

namespace markerbench {

// The data folder (…/share/markerbench), whether or not it exists.
std::string DataDir();

// DataDir()/relative_path; throws std::runtime_error naming the path when it is missing.
std::string DataFile(const std::string& relative_path);

}  // namespace markerbench
