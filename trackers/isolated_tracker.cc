#include "trackers/isolated_tracker.h"

#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace markerbench {
namespace {

using Clock = std::chrono::steady_clock;

// The worker's end of the socket pair, moved to this descriptor before every other one is
// closed (other threads' workers must see their parent's end close).
constexpr int kWorkerFd = 3;

// A message is its byte count (uint64) then its bytes. Both ends are the same program image,
// so numbers go as raw bytes.
class ByteWriter {
 public:
  template <typename T>
  void Put(const T& value) {
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void PutBytes(const void* data, size_t size) {
    Put<uint64_t>(size);
    bytes_.append(static_cast<const char*>(data), size);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  T Get() {
    T value;
    std::memcpy(&value, Take(sizeof(T)), sizeof(T));
    return value;
  }
  std::string GetBytes() {
    const auto size = Get<uint64_t>();
    return std::string(Take(size), size);
  }

 private:
  const char* Take(size_t size) {
    if (size > bytes_.size() - pos_) throw std::runtime_error("truncated worker message");
    pos_ += size;
    return bytes_.data() + pos_ - size;
  }
  const std::string& bytes_;
  size_t pos_ = 0;
};

// Waits until `fd` is ready for `events` or the deadline passes (false).
bool WaitFor(int fd, short events, Clock::time_point deadline) {
  for (;;) {
    int timeout_ms = -1;
    if (deadline != Clock::time_point::max()) {
      const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
      if (left.count() <= 0) return false;
      timeout_ms = static_cast<int>(std::min<long long>(left.count(), 1 << 30));
    }
    pollfd p{fd, events, 0};
    const int n = ::poll(&p, 1, timeout_ms);
    if (n > 0) return true;
    if (n < 0 && errno != EINTR) throw std::system_error(errno, std::generic_category(), "poll");
  }
}

enum class Io { kDone, kClosed, kTimedOut };

Io SendAll(int fd, const std::string& bytes, Clock::time_point deadline) {
  size_t sent = 0;
  while (sent < bytes.size()) {
    if (!WaitFor(fd, POLLOUT, deadline)) return Io::kTimedOut;
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) return Io::kClosed;  // EPIPE, ECONNRESET: the other end is gone
    sent += static_cast<size_t>(n);
  }
  return Io::kDone;
}

Io ReceiveExactly(int fd, size_t size, std::string* bytes, Clock::time_point deadline) {
  bytes->resize(size);
  size_t received = 0;
  while (received < size) {
    if (!WaitFor(fd, POLLIN, deadline)) return Io::kTimedOut;
    const ssize_t n = ::recv(fd, bytes->data() + received, size - received, 0);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) return Io::kClosed;
    received += static_cast<size_t>(n);
  }
  return Io::kDone;
}

Io SendMessage(int fd, const std::string& payload, Clock::time_point deadline) {
  ByteWriter framed;
  framed.PutBytes(payload.data(), payload.size());
  return SendAll(fd, framed.bytes(), deadline);
}

Io ReceiveMessage(int fd, std::string* payload, Clock::time_point deadline) {
  std::string size_bytes;
  const Io io = ReceiveExactly(fd, sizeof(uint64_t), &size_bytes, deadline);
  if (io != Io::kDone) return io;
  return ReceiveExactly(fd, ByteReader(size_bytes).Get<uint64_t>(), payload, deadline);
}

std::string EncodeResult(const TrackResult& result, double time_ms) {
  ByteWriter out;
  out.Put<uint8_t>(static_cast<uint8_t>(result.status));
  out.Put(time_ms);
  out.Put<uint64_t>(result.hypotheses.size());
  for (const Rigid3& pose : result.hypotheses) {
    out.PutBytes(pose.rotation.data(), 9 * sizeof(double));
    out.PutBytes(pose.translation.data(), 3 * sizeof(double));
  }
  out.Put<uint64_t>(result.keypoints_px.size());
  for (const Eigen::Vector2d& p : result.keypoints_px) out.PutBytes(p.data(), 2 * sizeof(double));
  out.PutBytes(result.message.data(), result.message.size());
  return out.bytes();
}

TrackResult DecodeResult(const std::string& bytes) {
  ByteReader in(bytes);
  TrackResult result;
  const auto status = in.Get<uint8_t>();
  if (status > static_cast<uint8_t>(TrackStatus::kError)) {
    throw std::runtime_error("unknown status in a worker message");
  }
  result.status = static_cast<TrackStatus>(status);
  result.time_ms = in.Get<double>();
  const auto hypotheses = in.Get<uint64_t>();
  for (uint64_t i = 0; i < hypotheses; ++i) {
    Rigid3 pose;
    const std::string rotation = in.GetBytes(), translation = in.GetBytes();
    if (rotation.size() != 9 * sizeof(double) || translation.size() != 3 * sizeof(double)) {
      throw std::runtime_error("malformed pose in a worker message");
    }
    std::memcpy(pose.rotation.data(), rotation.data(), rotation.size());
    std::memcpy(pose.translation.data(), translation.data(), translation.size());
    result.hypotheses.push_back(pose);
  }
  const auto keypoints = in.Get<uint64_t>();
  for (uint64_t i = 0; i < keypoints; ++i) {
    const std::string p = in.GetBytes();
    if (p.size() != 2 * sizeof(double)) throw std::runtime_error("malformed keypoint");
    Eigen::Vector2d point;
    std::memcpy(point.data(), p.data(), p.size());
    result.keypoints_px.push_back(point);
  }
  result.message = in.GetBytes();
  return result;
}

TrackResult ErrorResult(const std::string& message) {
  TrackResult result;
  result.status = TrackStatus::kError;
  result.message = message;
  return result;
}

// The worker: builds its tracker and answers requests until its parent's end closes.
[[noreturn]] void ServeRequests(const IsolatedTracker::Factory& make,
                                const Camera* camera,
                                const std::vector<MarkerSpec>* markers) {
  std::unique_ptr<Tracker> tracker = make();
  std::string request;
  while (ReceiveMessage(kWorkerFd, &request, Clock::time_point::max()) == Io::kDone) {
    ByteReader in(request);
    const auto reset = in.Get<uint8_t>();
    const auto marker = in.Get<uint64_t>();
    Image8 image;
    image.width = in.Get<int>();
    image.height = in.Get<int>();
    image.channels = in.Get<int>();
    const std::string pixels = in.GetBytes();
    image.pixels.assign(pixels.begin(), pixels.end());
    if (reset) tracker->Reset();
    const auto start = Clock::now();
    const TrackResult result =
        TrackCatchingExceptions(tracker.get(), {&image, camera, &(*markers)[marker]});
    const double time_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (SendMessage(kWorkerFd, EncodeResult(result, time_ms), Clock::time_point::max()) !=
        Io::kDone) {
      break;
    }
  }
  ::_exit(0);
}

}  // namespace

IsolatedTracker::IsolatedTracker(Factory make,
                                 const Camera* camera,
                                 const std::vector<MarkerSpec>* markers,
                                 IsolatedTrackerOptions options)
    : make_(std::move(make)),
      local_(make_()),
      camera_(camera),
      markers_(markers),
      options_(options) {}

IsolatedTracker::~IsolatedTracker() {
  if (pid_ > 0) StopWorker();
}

void IsolatedTracker::StartWorker() {
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0) {
    throw std::system_error(errno, std::generic_category(), "socketpair for a tracker worker");
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(ends[0]);
    ::close(ends[1]);
    throw std::system_error(error, std::generic_category(), "fork of a tracker worker");
  }
  if (pid == 0) {
    // Only this thread exists here; keep the standard streams and our end, nothing else.
    if (::dup2(ends[1], kWorkerFd) < 0) ::_exit(126);
    ::close_range(kWorkerFd + 1, ~0U, 0);
    ::signal(SIGPIPE, SIG_DFL);
    try {
      ServeRequests(make_, camera_, markers_);
    } catch (...) {
      ::_exit(127);
    }
  }
  ::close(ends[1]);
  pid_ = pid;
  socket_ = ends[0];
  reset_pending_ = true;  // a new worker starts from a fresh tracker
}

std::string IsolatedTracker::StopWorker() {
  ::close(socket_);
  socket_ = -1;
  int status = 0;
  // A worker that is done has exited; one that is not is killed (a hang, a protocol error).
  if (::waitpid(pid_, &status, WNOHANG) == 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
  }
  pid_ = -1;
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return std::string("killed by signal ") + std::to_string(signal) + " (" + ::strsignal(signal) +
           ")";
  }
  return "exited with status " + std::to_string(WEXITSTATUS(status));
}

TrackResult IsolatedTracker::WorkerFailed(const std::string& why) {
  return ErrorResult("tracker worker " + why + "; restarted for the next frame");
}

TrackResult IsolatedTracker::Track(const Observation& observation) {
  if (auto unusable = UnusableImage(observation)) return *unusable;
  size_t marker = 0;
  while (marker < markers_->size() && &(*markers_)[marker] != observation.marker) ++marker;
  if (observation.camera != camera_ || marker == markers_->size()) {
    return ErrorResult("isolated tracker: the camera or marker is not one the worker was given");
  }
  if (pid_ < 0) StartWorker();
  const Image8& image = *observation.image;
  ByteWriter request;
  request.Put<uint8_t>(reset_pending_ ? 1 : 0);
  request.Put<uint64_t>(marker);
  request.Put(image.width);
  request.Put(image.height);
  request.Put(image.channels);
  request.PutBytes(image.pixels.data(), image.pixels.size());
  reset_pending_ = false;

  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(options_.timeout_s));
  std::string reply;
  Io io = SendMessage(socket_, request.bytes(), deadline);
  if (io == Io::kDone) io = ReceiveMessage(socket_, &reply, deadline);
  if (io == Io::kTimedOut) {
    StopWorker();
    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%g", options_.timeout_s);
    return WorkerFailed(std::string("timed out after ") + seconds + " s and was killed");
  }
  if (io == Io::kClosed) return WorkerFailed(StopWorker());
  try {
    return DecodeResult(reply);
  } catch (const std::runtime_error& e) {
    StopWorker();
    return WorkerFailed(std::string("sent a bad reply (") + e.what() + ") and was killed");
  }
}

}  // namespace markerbench
