#include "trackers/isolated/isolated_tracker.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "core/number_text.h"
#include "trackers/isolated/worker_protocol.h"

extern char** environ;

namespace markerbench {
namespace {

int64_t DeadlineAfter(double seconds) {
  return SteadyNowMs() + static_cast<int64_t>(std::ceil(seconds * 1000.0));
}

std::string ErrnoText(const std::string& call) { return call + ": " + std::strerror(errno); }

// How a reaped worker ended, as the error row says it.
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

IsolatedTracker::IsolatedTracker(std::unique_ptr<Tracker> local, IsolationOptions options)
    : local_(std::move(local)), options_(std::move(options)) {
  std::string error;
  if (!Start(&error)) {
    throw std::runtime_error("cannot start the worker process " + options_.worker_argv.at(0) +
                             ": " + error);
  }
}

IsolatedTracker::~IsolatedTracker() {
  if (pid_ > 0) Stop(false);
}

std::vector<std::pair<std::string, std::string>> IsolationParameters(double timeout_s) {
  return {{"isolated", "true"}, {"timeout_s", NumberText(timeout_s)}};
}

std::vector<std::pair<std::string, std::string>> IsolatedTracker::Parameters() const {
  std::vector<std::pair<std::string, std::string>> parameters = local_->Parameters();
  for (auto& parameter : IsolationParameters(options_.timeout_s)) parameters.push_back(parameter);
  return parameters;
}

bool IsolatedTracker::Start(std::string* error) {
  int sockets[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0) {
    *error = ErrnoText("socketpair");
    return false;
  }
  // dup2 onto itself would keep close-on-exec, so the worker's end must not already be 3.
  if (sockets[1] == kWorkerFd) {
    const int moved = fcntl(sockets[1], F_DUPFD_CLOEXEC, kWorkerFd + 1);
    close(sockets[1]);
    sockets[1] = moved;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, sockets[1], kWorkerFd);
  // The worker starts with every signal at its default and none blocked.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, all;
  sigemptyset(&none);
  sigfillset(&all);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &all);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> argv;
  for (const std::string& arg : options_.worker_argv)
    argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  const int spawned = posix_spawn(&pid_, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  close(sockets[1]);
  if (spawned != 0) {
    close(sockets[0]);
    pid_ = -1;
    *error = std::string("posix_spawn: ") + std::strerror(spawned);
    return false;
  }
  socket_ = sockets[0];
  std::string ready;
  if (!ReceiveMessage(socket_, &ready, DeadlineAfter(options_.start_timeout_s), error)) {
    *error = "no ready message (" + *error + "); the worker " + Stop(true);
    return false;
  }
  reset_pending_ = true;
  return true;
}

std::string IsolatedTracker::Stop(bool kill) {
  close(socket_);  // a healthy worker exits at the close
  socket_ = -1;
  if (kill) ::kill(pid_, SIGKILL);
  int status = 0;
  // A worker that does not exit within a second of the close is killed.
  for (int waited_ms = 0;; waited_ms += 10) {
    const pid_t reaped = waitpid(pid_, &status, WNOHANG);
    if (reaped == pid_ || (reaped < 0 && errno != EINTR)) break;
    if (waited_ms == 1000) ::kill(pid_, SIGKILL);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  pid_ = -1;
  return DescribeEnd(status);
}

TrackResult IsolatedTracker::Track(const Observation& observation) {
  if (std::optional<TrackResult> unusable = UnusableImage(observation)) return *unusable;
  TrackResult failure;
  failure.status = TrackStatus::kError;
  std::string error;
  if (pid_ < 0 && !Start(&error)) {
    failure.message = "cannot restart the worker process: " + error;
    return failure;
  }
  const int64_t deadline = DeadlineAfter(options_.timeout_s);
  std::string reply;
  if (!SendMessage(socket_, EncodeRequest(reset_pending_, observation), deadline, &error) ||
      !ReceiveMessage(socket_, &reply, deadline, &error)) {
    const bool timed_out = error == "timed out";
    const std::string end = Stop(timed_out);
    failure.message = timed_out ? "no result within timeout_s " + NumberText(options_.timeout_s) +
                                      " s; the worker was stopped"
                                : "the worker " + end + " on this frame";
    return failure;
  }
  reset_pending_ = false;
  try {
    WorkerReply decoded = DecodeReply(reply);
    decoded.result.time_ms = decoded.time_ms;
    return decoded.result;
  } catch (const std::exception& e) {
    Stop(true);
    failure.message = std::string("malformed reply from the worker: ") + e.what();
    return failure;
  }
}

}  // namespace markerbench
