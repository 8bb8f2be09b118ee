#include "trackers/process/socket_io.h"

#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>

namespace markerbench {
namespace {

// Waits until `fd` is ready for `events` or the deadline passes.
bool WaitFor(int fd, int16_t events, std::optional<int64_t> deadline_ms, std::string* error) {
  for (;;) {
    int timeout = -1;
    if (deadline_ms) {
      const int64_t left = *deadline_ms - SteadyNowMs();
      if (left <= 0) {
        *error = kTimedOut;
        return false;
      }
      timeout = static_cast<int>(std::min<int64_t>(left, 1 << 30));
    }
    pollfd p{fd, events, 0};
    const int ready = poll(&p, 1, timeout);
    if (ready > 0) return true;
    if (ready < 0 && errno != EINTR) {
      *error = std::string("poll: ") + std::strerror(errno);
      return false;
    }
  }
}

// Up to `size` bytes into `data`; the count, or -1 with `*error` set.
ssize_t ReceiveSome(
    int fd, char* data, size_t size, std::optional<int64_t> deadline_ms, std::string* error) {
  for (;;) {
    if (!WaitFor(fd, POLLIN, deadline_ms, error)) return -1;
    const ssize_t got = recv(fd, data, size, 0);
    if (got > 0) return got;
    if (got == 0) {
      *error = "connection closed";
      return -1;
    }
    if (errno != EINTR && errno != EAGAIN) {
      *error = std::string("recv: ") + std::strerror(errno);
      return -1;
    }
  }
}

}  // namespace

int64_t SteadyNowMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

int64_t DeadlineAfter(double seconds) {
  return SteadyNowMs() + static_cast<int64_t>(std::ceil(seconds * 1000.0));
}

bool SendAll(int fd,
             const std::string& bytes,
             std::optional<int64_t> deadline_ms,
             std::string* error) {
  size_t sent = 0;
  while (sent < bytes.size()) {
    if (!WaitFor(fd, POLLOUT, deadline_ms, error)) return false;
    const ssize_t n = send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      *error = errno == EPIPE ? "connection closed" : std::string("send: ") + std::strerror(errno);
      return false;
    }
    sent += static_cast<size_t>(n);
  }
  return true;
}

bool ReceiveExactly(
    int fd, char* data, size_t size, std::optional<int64_t> deadline_ms, std::string* error) {
  while (size > 0) {
    const ssize_t got = ReceiveSome(fd, data, size, deadline_ms, error);
    if (got < 0) return false;
    data += got;
    size -= static_cast<size_t>(got);
  }
  return true;
}

bool ReceiveLine(int fd,
                 std::string* pending,
                 std::string* line,
                 size_t max_bytes,
                 std::optional<int64_t> deadline_ms,
                 std::string* error) {
  for (;;) {
    const size_t end = pending->find('\n');
    if (end != std::string::npos) {
      *line = pending->substr(0, end);
      pending->erase(0, end + 1);
      return true;
    }
    if (pending->size() > max_bytes) {
      *error = "a line longer than " + std::to_string(max_bytes) + " bytes";
      return false;
    }
    char chunk[65536];
    const ssize_t got = ReceiveSome(fd, chunk, sizeof(chunk), deadline_ms, error);
    if (got < 0) return false;
    pending->append(chunk, static_cast<size_t>(got));
  }
}

}  // namespace markerbench
