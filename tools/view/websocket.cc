// RFC 6455 framing and handshake; SHA-1 per FIPS 180-4 §6.1.
#include "view/websocket.h"

#include <array>

namespace vb::view {

namespace {

uint32_t RotateLeft(uint32_t x, int n) { return (x << n) | (x >> (32 - n)); }

// The GUID every WebSocket server appends to the client's key (RFC 6455 §1.3).
constexpr const char* kWebSocketGuid = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11";

}  // namespace

std::string Sha1(const std::string& data) {
  uint32_t h[5] = {0x67452301u, 0xEFCDAB89u, 0x98BADCFEu, 0x10325476u, 0xC3D2E1F0u};
  std::string msg = data;
  const uint64_t bit_length = static_cast<uint64_t>(data.size()) * 8u;
  msg.push_back(static_cast<char>(0x80));
  while (msg.size() % 64 != 56) msg.push_back('\0');
  for (int i = 7; i >= 0; --i) msg.push_back(static_cast<char>((bit_length >> (8 * i)) & 0xFF));

  std::array<uint32_t, 80> w{};
  for (size_t block = 0; block < msg.size(); block += 64) {
    for (int t = 0; t < 16; ++t) {
      const auto byte = [&](int k) {
        return static_cast<uint32_t>(static_cast<unsigned char>(msg[block + 4 * t + k]));
      };
      w[t] = (byte(0) << 24) | (byte(1) << 16) | (byte(2) << 8) | byte(3);
    }
    for (int t = 16; t < 80; ++t) w[t] = RotateLeft(w[t - 3] ^ w[t - 8] ^ w[t - 14] ^ w[t - 16], 1);
    uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4];
    for (int t = 0; t < 80; ++t) {
      uint32_t f, k;
      if (t < 20) {
        f = (b & c) | (~b & d);
        k = 0x5A827999u;
      } else if (t < 40) {
        f = b ^ c ^ d;
        k = 0x6ED9EBA1u;
      } else if (t < 60) {
        f = (b & c) | (b & d) | (c & d);
        k = 0x8F1BBCDCu;
      } else {
        f = b ^ c ^ d;
        k = 0xCA62C1D6u;
      }
      const uint32_t temp = RotateLeft(a, 5) + f + e + k + w[t];
      e = d;
      d = c;
      c = RotateLeft(b, 30);
      b = a;
      a = temp;
    }
    h[0] += a;
    h[1] += b;
    h[2] += c;
    h[3] += d;
    h[4] += e;
  }
  std::string digest;
  for (uint32_t v : h) {
    for (int i = 3; i >= 0; --i) digest.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
  }
  return digest;
}

std::string Base64(const std::string& bytes) {
  static const char* kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  const size_t rest = bytes.size() - i;
  if (rest > 0) {
    uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
    if (rest == 2) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string WebSocketAccept(const std::string& client_key) {
  return Base64(Sha1(client_key + kWebSocketGuid));
}

WsDecode DecodeClientFrame(const std::string& buffer, WsFrame* frame, size_t* consumed,
                           std::string* error) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(buffer[i]); };
  if (buffer.size() < 2) return WsDecode::kIncomplete;
  const bool fin = (byte(0) & 0x80) != 0;
  if ((byte(0) & 0x70) != 0) {
    *error = "reserved bits set (no extension was negotiated)";
    return WsDecode::kBad;
  }
  const uint8_t opcode = byte(0) & 0x0F;
  const bool control = (opcode & 0x08) != 0;
  if (opcode != 0x0 && opcode != 0x1 && opcode != 0x2 && opcode != 0x8 && opcode != 0x9 &&
      opcode != 0xA) {
    *error = "reserved opcode " + std::to_string(opcode);
    return WsDecode::kBad;
  }
  if ((byte(1) & 0x80) == 0) {
    *error = "client frame is not masked (RFC 6455 5.1)";
    return WsDecode::kBad;
  }
  uint64_t length = byte(1) & 0x7F;
  size_t pos = 2;
  if (length == 126) {
    if (buffer.size() < 4) return WsDecode::kIncomplete;
    length = (static_cast<uint64_t>(byte(2)) << 8) | byte(3);
    pos = 4;
  } else if (length == 127) {
    if (buffer.size() < 10) return WsDecode::kIncomplete;
    length = 0;
    for (int i = 0; i < 8; ++i) length = (length << 8) | byte(2 + i);
    pos = 10;
  }
  if (control && (length > 125 || !fin)) {
    *error = "control frame fragmented or longer than 125 bytes";
    return WsDecode::kBad;
  }
  if (length > kMaxClientPayloadBytes) {
    *error = "frame payload of " + std::to_string(length) + " bytes exceeds the limit of " +
             std::to_string(kMaxClientPayloadBytes);
    return WsDecode::kBad;
  }
  if (buffer.size() < pos + 4 + length) return WsDecode::kIncomplete;
  const size_t mask_at = pos;
  pos += 4;
  frame->fin = fin;
  frame->opcode = static_cast<WsOpcode>(opcode);
  frame->payload.resize(length);
  for (size_t i = 0; i < length; ++i) {
    frame->payload[i] = static_cast<char>(byte(pos + i) ^ byte(mask_at + i % 4));
  }
  *consumed = pos + length;
  return WsDecode::kFrame;
}

namespace {

std::string FrameHeader(WsOpcode opcode, size_t length, bool masked) {
  std::string h;
  h.push_back(static_cast<char>(0x80 | static_cast<uint8_t>(opcode)));
  const uint8_t mask_bit = masked ? 0x80 : 0x00;
  if (length < 126) {
    h.push_back(static_cast<char>(mask_bit | length));
  } else if (length <= 0xFFFF) {
    h.push_back(static_cast<char>(mask_bit | 126));
    h.push_back(static_cast<char>((length >> 8) & 0xFF));
    h.push_back(static_cast<char>(length & 0xFF));
  } else {
    h.push_back(static_cast<char>(mask_bit | 127));
    for (int i = 7; i >= 0; --i) {
      h.push_back(static_cast<char>((static_cast<uint64_t>(length) >> (8 * i)) & 0xFF));
    }
  }
  return h;
}

}  // namespace

std::string EncodeServerFrame(WsOpcode opcode, const std::string& payload) {
  return FrameHeader(opcode, payload.size(), false) + payload;
}

std::string EncodeClientFrame(WsOpcode opcode, const std::string& payload, uint32_t mask_key) {
  std::string out = FrameHeader(opcode, payload.size(), true);
  char mask[4];
  for (int i = 0; i < 4; ++i) mask[i] = static_cast<char>((mask_key >> (24 - 8 * i)) & 0xFF);
  out.append(mask, 4);
  for (size_t i = 0; i < payload.size(); ++i) out.push_back(payload[i] ^ mask[i % 4]);
  return out;
}

}  // namespace vb::view
