// Frame reading and writing over raw file descriptors (no stdio buffering: a reply must reach the
// client as soon as it is written, and a partial read must not be lost in a buffer).
#include "frame.h"

#include <errno.h>
#include <unistd.h>

#include <cstring>

namespace vb::gym {

namespace {

// Reads exactly n bytes. Returns n on success, 0 on EOF before the first byte, -1 on EOF in the
// middle or a read error.
long ReadExact(int fd, uint8_t* out, size_t n) {
  size_t got = 0;
  while (got < n) {
    const ssize_t r = ::read(fd, out + got, n - got);
    if (r > 0) {
      got += static_cast<size_t>(r);
    } else if (r == 0) {
      return got == 0 ? 0 : -1;
    } else if (errno != EINTR) {
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
  const long r = ReadExact(fd, prefix, sizeof(prefix));
  if (r == 0) return ReadStatus::kEof;
  if (r < 0) {
    *error = "truncated frame prefix (the client closed the stream inside a frame)";
    return ReadStatus::kFramingError;
  }
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
  if (ReadExact(fd, reinterpret_cast<uint8_t*>(&frame->header[0]), header_bytes) !=
      static_cast<long>(header_bytes)) {
    *error = "truncated frame header";
    return ReadStatus::kFramingError;
  }
  frame->payload.resize(payload_bytes);
  if (payload_bytes > 0 && ReadExact(fd, frame->payload.data(), payload_bytes) !=
                               static_cast<long>(payload_bytes)) {
    *error = "truncated frame payload";
    return ReadStatus::kFramingError;
  }
  return ReadStatus::kOk;
}

bool WriteFrame(int fd, const std::string& header, const std::vector<uint8_t>& payload) {
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
