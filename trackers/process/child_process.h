// A child process started with posix_spawn (safe in a multithreaded process, unlike fork:
// the child of a fork may need a lock another thread held) and connected by one stream
// socket.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace markerbench {

struct ChildSpec {
  // The program and its arguments; argv[0] is searched in PATH when it holds no '/'.
  std::vector<std::string> argv;
  // Where the child sees its end of the socket: {3}, or {0, 1} for standard input and output.
  // Standard input is /dev/null and standard output goes to standard error unless listed.
  std::vector<int> socket_fds;
  // The child's standard error is appended to this file; empty: this process's.
  std::string stderr_path;
  // The child's working folder; empty: this process's.
  std::string working_dir;
};

class ChildProcess {
 public:
  ChildProcess() = default;
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // False with `*error` set when the child cannot be started. The child starts with every
  // signal at its default and none blocked.
  bool Start(const ChildSpec& spec, std::string* error);
  bool running() const { return pid_ > 0; }
  int socket() const { return socket_; }
  // Closes the socket and reaps the child, killing it first when `kill` or when it has not
  // exited a second after the close. Says how it ended: "exited with status 0", "was killed by
  // signal SIGSEGV".
  std::string Stop(bool kill);

 private:
  pid_t pid_ = -1;
  int socket_ = -1;
};

}  // namespace markerbench
