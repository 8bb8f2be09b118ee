// Blocking I/O with a deadline on the stream socket to a child process. Deadlines are
// SteadyNowMs() values; nullopt waits forever. Each call returns false with `*error` set on a
// timeout (kTimedOut), a closed peer ("connection closed") or a system error; sends never
// raise SIGPIPE.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace markerbench {

constexpr const char* kTimedOut = "timed out";

int64_t SteadyNowMs();
int64_t DeadlineAfter(double seconds);

bool SendAll(int fd,
             const std::string& bytes,
             std::optional<int64_t> deadline_ms,
             std::string* error);
bool ReceiveExactly(
    int fd, char* data, size_t size, std::optional<int64_t> deadline_ms, std::string* error);
// The next line, without its '\n', in `*line`; bytes received after it stay in `*pending` for
// the next call. A line longer than `max_bytes` is an error.
bool ReceiveLine(int fd,
                 std::string* pending,
                 std::string* line,
                 size_t max_bytes,
                 std::optional<int64_t> deadline_ms,
                 std::string* error);

}  // namespace markerbench
