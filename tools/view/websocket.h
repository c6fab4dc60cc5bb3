// The WebSocket protocol (RFC 6455) as far as vb_view needs it: the opening handshake's accept
// key (SHA-1 + base64, both here because nothing else in vb needs them) and frames. A server
// receives masked frames from the browser and sends unmasked ones. No I/O here: the server
// (view_server.cc) owns the sockets, which keeps this testable with byte strings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace vb::view {

// SHA-1 digest (20 bytes) of `data` (FIPS 180-4).
std::string Sha1(const std::string& data);
// Standard base64 with padding (RFC 4648 §4).
std::string Base64(const std::string& bytes);
// Sec-WebSocket-Accept for a client's Sec-WebSocket-Key (RFC 6455 §4.2.2).
std::string WebSocketAccept(const std::string& client_key);

enum class WsOpcode : uint8_t {
  kContinuation = 0x0,
  kText = 0x1,
  kBinary = 0x2,
  kClose = 0x8,
  kPing = 0x9,
  kPong = 0xA,
};

struct WsFrame {
  bool fin = true;
  WsOpcode opcode = WsOpcode::kText;
  std::string payload;   // unmasked
};

enum class WsDecode { kIncomplete, kFrame, kBad };

// Largest client frame payload accepted: the page sends short commands; anything bigger is a
// protocol error (and bounds the memory a misbehaving client can make the server hold).
constexpr size_t kMaxClientPayloadBytes = 64 * 1024;

// Decodes one client frame from the start of `buffer`. kFrame: *frame filled and *consumed bytes
// used; kIncomplete: more bytes needed; kBad: *error says why (unmasked client frame, reserved
// bits or opcode, oversized payload, fragmented control frame).
WsDecode DecodeClientFrame(const std::string& buffer, WsFrame* frame, size_t* consumed,
                           std::string* error);
// One unmasked server frame with FIN set.
std::string EncodeServerFrame(WsOpcode opcode, const std::string& payload);
// A masked client frame (for tests and for clients written in C++).
std::string EncodeClientFrame(WsOpcode opcode, const std::string& payload, uint32_t mask_key);

}  // namespace vb::view
