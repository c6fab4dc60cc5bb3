// The frames of the vb_gym protocol (docs/gym_protocol.md): a fixed 8-byte prefix (header length
// and payload length, uint32 little-endian), a UTF-8 JSON header, then the payload: raw
// little-endian arrays, one after the other, described by the header's "arrays" list. Raw
// arrays let a 64 x 64 crop cross the pipe without any text encoding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vb::gym {

// Largest header and payload a peer may announce; anything larger is a framing error (the stream
// cannot be trusted after it).
constexpr uint32_t kMaxHeaderBytes = 1u << 20;
constexpr uint32_t kMaxPayloadBytes = 256u << 20;
// Deepest nesting of objects and lists in a request header (the protocol's own requests nest 3
// levels); deeper is an error reply, before anything recurses over the value.
constexpr int kMaxHeaderDepth = 32;
// Once a frame's first byte has arrived, the rest must follow within this time (between frames
// the client may take as long as it likes): a client stuck inside a frame is a framing error, not
// a server that waits forever.
constexpr double kFrameCompletionLimit_s = 60.0;

struct Frame {
  std::string header;             // JSON text
  std::vector<uint8_t> payload;   // raw arrays
};

enum class ReadStatus {
  kOk,
  kEof,           // the peer closed the stream cleanly between frames
  kFramingError,  // truncated or stalled frame, or lengths beyond the limits (message says which)
};

// Reads one frame from file descriptor fd (blocking until its first byte, then at most
// kFrameCompletionLimit_s for the rest). The payload buffer grows with the bytes that arrive,
// not with the length the prefix announces. On kFramingError *error says what.
ReadStatus ReadFrame(int fd, Frame* frame, std::string* error);

// Writes one frame; false if the peer has gone (EPIPE) or the write failed, and false without
// writing anything for a header or payload above the limits (a uint32 length never wraps).
bool WriteFrame(int fd, const std::string& header, const std::vector<uint8_t>& payload);

// Appends the raw little-endian bytes of `values` to *payload (the host must be little-endian:
// checked once at start-up by HostIsLittleEndian).
void AppendFloat32(const std::vector<double>& values, std::vector<uint8_t>* payload);
void AppendFloat64(const std::vector<double>& values, std::vector<uint8_t>* payload);
bool HostIsLittleEndian();

}  // namespace vb::gym
