#include "trackers/isolated/worker_protocol.h"

#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "trackers/process/socket_io.h"

namespace markerbench {
namespace {

class ByteWriter {
 public:
  template <typename T>
  void Put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void PutBytes(const void* data, size_t size) {
    Put<uint64_t>(size);
    bytes_.append(static_cast<const char*>(data), size);
  }
  void PutString(const std::string& text) { PutBytes(text.data(), text.size()); }
  std::string Take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  T Get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, Take(sizeof(T)), sizeof(T));
    return value;
  }
  // A count that the rest of the body can hold at `item_bytes` each.
  size_t GetCount(size_t item_bytes) {
    const uint64_t count = Get<uint64_t>();
    if (count > (bytes_.size() - at_) / item_bytes) throw std::runtime_error("count too large");
    return static_cast<size_t>(count);
  }
  std::string GetString() {
    const size_t size = GetCount(1);
    return std::string(Take(size), size);
  }
  void ExpectEnd() const {
    if (at_ != bytes_.size()) throw std::runtime_error("trailing bytes");
  }
  const char* Take(size_t size) {
    if (size > bytes_.size() - at_) throw std::runtime_error("message too short");
    const char* data = bytes_.data() + at_;
    at_ += size;
    return data;
  }

 private:
  const std::string& bytes_;
  size_t at_ = 0;
};

void PutPose(ByteWriter& out, const Rigid3& pose) {
  for (int k = 0; k < 9; ++k) out.Put<double>(pose.rotation(k / 3, k % 3));
  for (int k = 0; k < 3; ++k) out.Put<double>(pose.translation[k]);
}

Rigid3 GetPose(ByteReader& in) {
  Rigid3 pose;
  for (int k = 0; k < 9; ++k) pose.rotation(k / 3, k % 3) = in.Get<double>();
  for (int k = 0; k < 3; ++k) pose.translation[k] = in.Get<double>();
  return pose;
}

}  // namespace

std::string EncodeRequest(bool reset, const Observation& observation) {
  ByteWriter out;
  out.Put<uint8_t>(reset ? 1 : 0);
  out.PutString(observation.marker->name);
  const Camera& camera = *observation.camera;
  out.PutString(camera.name);
  out.Put<int32_t>(camera.width);
  out.Put<int32_t>(camera.height);
  for (const double v : {camera.fx, camera.fy, camera.cx, camera.cy}) out.Put<double>(v);
  for (const double v : camera.distortion) out.Put<double>(v);
  const Image8& image = *observation.image;
  out.Put<int32_t>(image.width);
  out.Put<int32_t>(image.height);
  out.Put<int32_t>(image.channels);
  out.PutBytes(image.pixels.data(), image.pixels.size());
  return out.Take();
}

WorkerRequest DecodeRequest(const std::string& body) {
  ByteReader in(body);
  WorkerRequest request;
  request.reset = in.Get<uint8_t>() != 0;
  request.marker_name = in.GetString();
  Camera& camera = request.camera;
  camera.name = in.GetString();
  camera.width = in.Get<int32_t>();
  camera.height = in.Get<int32_t>();
  for (double* v : {&camera.fx, &camera.fy, &camera.cx, &camera.cy}) *v = in.Get<double>();
  for (double& v : camera.distortion) v = in.Get<double>();
  Image8& image = request.image;
  image.width = in.Get<int32_t>();
  image.height = in.Get<int32_t>();
  image.channels = in.Get<int32_t>();
  const size_t size = in.GetCount(1);
  const char* pixels = in.Take(size);
  image.pixels.assign(pixels, pixels + size);
  in.ExpectEnd();
  return request;
}

std::string EncodeReply(const WorkerReply& reply) {
  ByteWriter out;
  const TrackResult& result = reply.result;
  out.Put<uint8_t>(static_cast<uint8_t>(result.status));
  out.PutString(result.message);
  out.Put<uint64_t>(result.hypotheses.size());
  for (const Rigid3& pose : result.hypotheses) PutPose(out, pose);
  out.Put<uint64_t>(result.keypoints_px.size());
  for (const Eigen::Vector2d& p : result.keypoints_px) {
    out.Put<double>(p.x());
    out.Put<double>(p.y());
  }
  out.Put<double>(reply.time_ms);
  return out.Take();
}

WorkerReply DecodeReply(const std::string& body) {
  ByteReader in(body);
  WorkerReply reply;
  TrackResult& result = reply.result;
  const uint8_t status = in.Get<uint8_t>();
  if (status > static_cast<uint8_t>(TrackStatus::kError)) {
    throw std::runtime_error("unknown status " + std::to_string(status));
  }
  result.status = static_cast<TrackStatus>(status);
  result.message = in.GetString();
  result.hypotheses.resize(in.GetCount(12 * sizeof(double)));
  for (Rigid3& pose : result.hypotheses) pose = GetPose(in);
  result.keypoints_px.resize(in.GetCount(2 * sizeof(double)));
  for (Eigen::Vector2d& p : result.keypoints_px) {
    p.x() = in.Get<double>();
    p.y() = in.Get<double>();
  }
  reply.time_ms = in.Get<double>();
  in.ExpectEnd();
  return reply;
}

bool SendMessage(int fd,
                 const std::string& body,
                 std::optional<int64_t> deadline_ms,
                 std::string* error) {
  if (body.size() > kMaxMessageBytes) {
    *error = "message of " + std::to_string(body.size()) + " bytes is too large";
    return false;
  }
  const uint32_t size = static_cast<uint32_t>(body.size());
  return SendAll(fd,
                 std::string(reinterpret_cast<const char*>(&size), sizeof(size)) + body,
                 deadline_ms,
                 error);
}

bool ReceiveMessage(int fd,
                    std::string* body,
                    std::optional<int64_t> deadline_ms,
                    std::string* error) {
  uint32_t size = 0;
  if (!ReceiveExactly(fd, reinterpret_cast<char*>(&size), sizeof(size), deadline_ms, error)) {
    return false;
  }
  if (size > kMaxMessageBytes) {
    *error = "message of " + std::to_string(size) + " bytes is too large";
    return false;
  }
  body->resize(size);
  return ReceiveExactly(fd, body->data(), size, deadline_ms, error);
}

}  // namespace markerbench
