#include "trackers/process/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

extern char** environ;

namespace markerbench {
namespace {

// How a reaped child ended.
std::string DescribeEnd(int status) {
  if (WIFSIGNALED(status)) {
    const char* name = sigabbrev_np(WTERMSIG(status));
    return std::string("was killed by signal ") +
           (name ? std::string("SIG") + name : std::to_string(WTERMSIG(status)));
  }
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  return "ended";
}

}  // namespace

ChildProcess::~ChildProcess() {
  if (running()) Stop(false);
}

bool ChildProcess::Start(const ChildSpec& spec, std::string* error) {
  int sockets[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0) {
    *error = std::string("socketpair: ") + std::strerror(errno);
    return false;
  }
  // Above every descriptor the child is given, so that no dup2 below overwrites it (and a
  // dup2 onto itself, which would keep close-on-exec, cannot happen).
  const int child_end = fcntl(sockets[1], F_DUPFD_CLOEXEC, 10);
  close(sockets[1]);
  if (child_end < 0) {
    *error = std::string("fcntl: ") + std::strerror(errno);
    close(sockets[0]);
    return false;
  }
  auto listed = [&](int fd) {
    return std::find(spec.socket_fds.begin(), spec.socket_fds.end(), fd) != spec.socket_fds.end();
  };
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!spec.stderr_path.empty()) {
    posix_spawn_file_actions_addopen(
        &actions, STDERR_FILENO, spec.stderr_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  }
  if (!listed(STDIN_FILENO)) {
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  }
  if (!listed(STDOUT_FILENO)) {
    posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  }
  for (const int fd : spec.socket_fds) posix_spawn_file_actions_adddup2(&actions, child_end, fd);
  if (!spec.working_dir.empty()) {
    posix_spawn_file_actions_addchdir_np(&actions, spec.working_dir.c_str());
  }
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, all;
  sigemptyset(&none);
  sigfillset(&all);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &all);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> argv;
  for (const std::string& arg : spec.argv) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const int spawned = posix_spawnp(&pid_, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  close(child_end);
  if (spawned != 0) {
    close(sockets[0]);
    pid_ = -1;
    *error = spec.argv[0] + ": " + std::strerror(spawned);
    return false;
  }
  socket_ = sockets[0];
  return true;
}

std::string ChildProcess::Stop(bool kill) {
  close(socket_);  // a healthy child exits at the close
  socket_ = -1;
  if (kill) ::kill(pid_, SIGKILL);
  int status = 0;
  for (int waited_ms = 0;; waited_ms += 10) {
    const pid_t reaped = waitpid(pid_, &status, WNOHANG);
    if (reaped == pid_ || (reaped < 0 && errno != EINTR)) break;
    if (waited_ms == 1000) ::kill(pid_, SIGKILL);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  pid_ = -1;
  return DescribeEnd(status);
}

}  // namespace markerbench
