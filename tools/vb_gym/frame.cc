// Frame reading and writing over raw file descriptors (no stdio buffering: a reply must reach the
// client as soon as it is written, and a partial read must not be lost in a buffer).
#include "frame.h"

#include <errno.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

namespace vb::gym {

namespace {

double Now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Reads exactly n bytes, waiting at most until `deadline_s` (Now_s() clock; <= 0: no limit).
// Returns n on success, 0 on EOF before the first byte, -1 on EOF in the middle or a read
// error, -2 when the deadline passed.
long ReadExact(int fd, uint8_t* out, size_t n, double deadline_s) {
  size_t got = 0;
  while (got < n) {
    if (deadline_s > 0.0) {
      const double left_s = deadline_s - Now_s();
      if (left_s <= 0.0) return -2;
      pollfd p{fd, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::ceil(left_s * 1000.0)));
      if (ready < 0 && errno != EINTR) return -1;
      if (ready <= 0) continue;
    }
    const ssize_t r = ::read(fd, out + got, n - got);
    if (r > 0) {
      got += static_cast<size_t>(r);
    } else if (r == 0) {
      return got == 0 ? 0 : -1;
    } else if (errno != EINTR && errno != EAGAIN) {
      return -1;
    }
  }
  return static_cast<long>(n);
}

bool WriteAll(int fd, const uint8_t* data, size_t n) {
  size_t done = 0;
  while (done < n) {
    const ssize_t w = ::write(fd, data + done, n - done);
    if (w > 0) {
      done += static_cast<size_t>(w);
    } else if (w < 0 && errno == EINTR) {
      continue;
    } else {
      return false;
    }
  }
  return true;
}

uint32_t LoadU32(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
         (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
}

void StoreU32(uint32_t v, uint8_t* p) {
  p[0] = static_cast<uint8_t>(v);
  p[1] = static_cast<uint8_t>(v >> 8);
  p[2] = static_cast<uint8_t>(v >> 16);
  p[3] = static_cast<uint8_t>(v >> 24);
}

}  // namespace

ReadStatus ReadFrame(int fd, Frame* frame, std::string* error) {
  uint8_t prefix[8];
  // The first byte without a time limit (the client decides when to send), the rest with one.
  const long first = ReadExact(fd, prefix, 1, 0.0);
  if (first == 0) return ReadStatus::kEof;
  const double deadline_s = Now_s() + kFrameCompletionLimit_s;
  const auto stalled = [&](long r, const char* part) {
    *error = r == -2 ? std::string("the client stalled inside a frame (") + part +
                           " incomplete after " + std::to_string(static_cast<int>(
                               kFrameCompletionLimit_s)) + " s)"
                     : std::string("truncated frame ") + part +
                           (std::string(part) == "prefix"
                                ? " (the client closed the stream inside a frame)" : "");
    return ReadStatus::kFramingError;
  };
  if (first < 0) return stalled(first, "prefix");
  const long rest = ReadExact(fd, prefix + 1, sizeof(prefix) - 1, deadline_s);
  if (rest != static_cast<long>(sizeof(prefix) - 1)) return stalled(rest == 0 ? -1 : rest, "prefix");
  const uint32_t header_bytes = LoadU32(prefix);
  const uint32_t payload_bytes = LoadU32(prefix + 4);
  if (header_bytes == 0 || header_bytes > kMaxHeaderBytes) {
    *error = "header length " + std::to_string(header_bytes) + " bytes out of range (1.." +
             std::to_string(kMaxHeaderBytes) + ")";
    return ReadStatus::kFramingError;
  }
  if (payload_bytes > kMaxPayloadBytes) {
    *error = "payload length " + std::to_string(payload_bytes) + " bytes above the limit of " +
             std::to_string(kMaxPayloadBytes);
    return ReadStatus::kFramingError;
  }
  frame->header.resize(header_bytes);
  const long h = ReadExact(fd, reinterpret_cast<uint8_t*>(&frame->header[0]), header_bytes,
                           deadline_s);
  if (h != static_cast<long>(header_bytes)) return stalled(h == 0 ? -1 : h, "header");
  // In chunks: memory follows what the client actually sends, not what it announces.
  constexpr size_t kChunkBytes = 1u << 20;
  frame->payload.clear();
  while (frame->payload.size() < payload_bytes) {
    const size_t at = frame->payload.size();
    const size_t n = std::min<size_t>(kChunkBytes, payload_bytes - at);
    frame->payload.resize(at + n);
    const long p = ReadExact(fd, frame->payload.data() + at, n, deadline_s);
    if (p != static_cast<long>(n)) return stalled(p == 0 ? -1 : p, "payload");
  }
  return ReadStatus::kOk;
}

bool WriteFrame(int fd, const std::string& header, const std::vector<uint8_t>& payload) {
  if (header.size() > kMaxHeaderBytes || payload.size() > kMaxPayloadBytes) return false;
  uint8_t prefix[8];
  StoreU32(static_cast<uint32_t>(header.size()), prefix);
  StoreU32(static_cast<uint32_t>(payload.size()), prefix + 4);
  return WriteAll(fd, prefix, sizeof(prefix)) &&
         WriteAll(fd, reinterpret_cast<const uint8_t*>(header.data()), header.size()) &&
         (payload.empty() || WriteAll(fd, payload.data(), payload.size()));
}

void AppendFloat32(const std::vector<double>& values, std::vector<uint8_t>* payload) {
  const size_t at = payload->size();
  payload->resize(at + values.size() * sizeof(float));
  for (size_t i = 0; i < values.size(); ++i) {
    const float f = static_cast<float>(values[i]);
    std::memcpy(payload->data() + at + i * sizeof(float), &f, sizeof(float));
  }
}

void AppendFloat64(const std::vector<double>& values, std::vector<uint8_t>* payload) {
  const size_t at = payload->size();
  payload->resize(at + values.size() * sizeof(double));
  if (!values.empty()) std::memcpy(payload->data() + at, values.data(), values.size() * sizeof(double));
}

bool HostIsLittleEndian() {
  const uint32_t one = 1;
  uint8_t first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

}  // namespace vb::gym
