// RFC 6455 framing and handshake, SHA-1 and base64 against their standards' test vectors.
#include "view/websocket.h"

#include <gtest/gtest.h>

#include <string>

namespace vb::view {
namespace {

std::string Hex(const std::string& bytes) {
  static const char* d = "0123456789abcdef";
  std::string out;
  for (unsigned char c : bytes) {
    out += d[c >> 4];
    out += d[c & 15];
  }
  return out;
}

TEST(WebSocketTest, Sha1MatchesFips180Vectors) {
  EXPECT_EQ(Hex(Sha1("")), "da39a3ee5e6b4b0d3255bfef95601890afd80709");
  EXPECT_EQ(Hex(Sha1("abc")), "a9993e364706816aba3e25717850c26c9cd0d89d");
  EXPECT_EQ(Hex(Sha1("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "84983e441c3bd26ebaae4aa1f95129e5e54670f1");
  // Two blocks' worth and a length that needs the padding to spill into a new block.
  EXPECT_EQ(Hex(Sha1(std::string(1000, 'a'))), "291e9a6c66994949b57ba5e650361e98fc36b1ba");
}

TEST(WebSocketTest, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
}

TEST(WebSocketTest, AcceptKeyIsRfc6455Example) {
  EXPECT_EQ(WebSocketAccept("dGhlIHNhbXBsZSBub25jZQ=="), "s3pPLMBiTxaQ9kYGzzhZRbK+xOo=");
}

TEST(WebSocketTest, DecodesRfc6455MaskedHello) {
  // RFC 6455 5.7: a single-frame masked text message "Hello".
  const std::string bytes("\x81\x85\x37\xfa\x21\x3d\x7f\x9f\x4d\x51\x58", 11);
  WsFrame f;
  size_t used = 0;
  std::string error;
  ASSERT_EQ(DecodeClientFrame(bytes, &f, &used, &error), WsDecode::kFrame) << error;
  EXPECT_EQ(f.payload, "Hello");
  EXPECT_EQ(f.opcode, WsOpcode::kText);
  EXPECT_TRUE(f.fin);
  EXPECT_EQ(used, 11u);
  // Every shorter prefix is incomplete, never a frame or an error.
  for (size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_EQ(DecodeClientFrame(bytes.substr(0, n), &f, &used, &error), WsDecode::kIncomplete) << n;
  }
}

TEST(WebSocketTest, RoundTripsAllLengthForms) {
  for (size_t length : {0u, 5u, 125u, 126u, 1000u, 65535u, 65536u}) {
    const std::string payload(length, 'x');
    const std::string bytes = EncodeClientFrame(WsOpcode::kBinary, payload, 0x12345678u) + "tail";
    WsFrame f;
    size_t used = 0;
    std::string error;
    ASSERT_EQ(DecodeClientFrame(bytes, &f, &used, &error), WsDecode::kFrame) << length << error;
    EXPECT_EQ(f.payload, payload);
    EXPECT_EQ(bytes.substr(used), "tail");
  }
  // Server frames: header sizes 2, 4 and 10 bytes.
  EXPECT_EQ(EncodeServerFrame(WsOpcode::kText, "hi"), std::string("\x81\x02hi", 4));
  EXPECT_EQ(EncodeServerFrame(WsOpcode::kText, std::string(200, 'a')).size(), 204u);
  EXPECT_EQ(EncodeServerFrame(WsOpcode::kText, std::string(70000, 'a')).size(), 70010u);
}

TEST(WebSocketTest, RejectsBadClientFrames) {
  WsFrame f;
  size_t used = 0;
  std::string error;
  // Unmasked (a server frame sent by a client).
  EXPECT_EQ(DecodeClientFrame(EncodeServerFrame(WsOpcode::kText, "hi"), &f, &used, &error),
            WsDecode::kBad);
  EXPECT_NE(error.find("not masked"), std::string::npos);
  // Reserved bits.
  std::string rsv = EncodeClientFrame(WsOpcode::kText, "hi", 1);
  rsv[0] = static_cast<char>(rsv[0] | 0x40);
  EXPECT_EQ(DecodeClientFrame(rsv, &f, &used, &error), WsDecode::kBad);
  // Reserved opcode.
  std::string op = EncodeClientFrame(WsOpcode::kText, "hi", 1);
  op[0] = static_cast<char>(0x83);
  EXPECT_EQ(DecodeClientFrame(op, &f, &used, &error), WsDecode::kBad);
  EXPECT_NE(error.find("opcode 3"), std::string::npos);
  // A control frame longer than 125 bytes.
  EXPECT_EQ(DecodeClientFrame(EncodeClientFrame(WsOpcode::kPing, std::string(126, 'p'), 1), &f,
                              &used, &error),
            WsDecode::kBad);
  // Oversized payload: rejected from the header alone, before the bytes arrive.
  const std::string big =
      EncodeClientFrame(WsOpcode::kText, std::string(kMaxClientPayloadBytes + 1, 'z'), 7);
  EXPECT_EQ(DecodeClientFrame(big.substr(0, 16), &f, &used, &error), WsDecode::kBad);
  EXPECT_NE(error.find("exceeds"), std::string::npos);
}

}  // namespace
}  // namespace vb::view
