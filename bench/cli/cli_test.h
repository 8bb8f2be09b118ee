// Test fixture: runs the markerbench binary (MARKERBENCH_BINARY) or another program as a
// subprocess, as users run it, in a fresh work folder; standard output and error go to files.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace markerbench {

// The source tree (tests run there).
inline const std::string kRoot = std::filesystem::current_path().string();

struct Finished {
  int status = -1;    // the exit status, or 128 + the signal
  std::string error;  // standard error
};

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ =
        std::filesystem::temp_directory_path() / ("markerbench_cli_" + std::to_string(::getpid()));
    std::filesystem::remove_all(work_);
    std::filesystem::create_directories(work_);
  }
  void TearDown() override { std::filesystem::remove_all(work_); }

  // Starts markerbench with `args`; standard error goes to work_/stderr.txt.
  pid_t Start(const std::vector<std::string>& args) {
    return StartProgram(MARKERBENCH_BINARY, args);
  }

  pid_t StartProgram(const std::string& program, const std::vector<std::string>& args) {
    std::vector<std::string> argv_text = {program};
    argv_text.insert(argv_text.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_text) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions,
                                     STDOUT_FILENO,
                                     (work_ / "stdout.txt").c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_addopen(&actions,
                                     STDERR_FILENO,
                                     (work_ / "stderr.txt").c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    pid_t pid = -1;
    EXPECT_EQ(posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    return pid;
  }

  Finished Wait(pid_t pid) {
    int status = 0;
    EXPECT_EQ(::waitpid(pid, &status, 0), pid);
    Finished f;
    f.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    f.error = Read(work_ / "stderr.txt");
    return f;
  }

  Finished Run(const std::vector<std::string>& args) { return Wait(Start(args)); }
  Finished RunProgram(const std::string& program, const std::vector<std::string>& args) {
    return Wait(StartProgram(program, args));
  }

  static std::string Read(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  static size_t Lines(const std::filesystem::path& path) {
    const std::string text = Read(path);
    return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
  }

  std::filesystem::path work_;
};

}  // namespace markerbench
