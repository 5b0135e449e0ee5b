#pragma once
// Little-endian byte buffers for the compact team encodings: fixed-width integers, float32,
// LEB128 varints (zigzag for signed), and a bounds-checked reader that never reads past the
// end (it records the first failure instead of throwing).
#include <cstdint>
#include <string>
#include <vector>

namespace slide::team {

using Bytes = std::vector<std::uint8_t>;

// Differences of ids and timestamps as sent (defined for any values, also untrusted ones:
// they wrap around instead of overflowing).
inline std::int64_t wrappingAdd(std::int64_t a, std::int64_t b) {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) + static_cast<std::uint64_t>(b));
}
inline std::int64_t wrappingSub(std::int64_t a, std::int64_t b) {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b));
}

class ByteWriter {
 public:
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { u8(static_cast<std::uint8_t>(v)), u8(static_cast<std::uint8_t>(v >> 8)); }
  void u32(std::uint32_t v);
  void u64(std::uint64_t v);
  void f32(float v);
  void varint(std::uint64_t v);
  void svarint(std::int64_t v) { varint((static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63)); }
  void bytes(const std::uint8_t* p, std::size_t n) { out_.insert(out_.end(), p, p + n); }
  const Bytes& data() const { return out_; }
  Bytes take() { return std::move(out_); }

 private:
  Bytes out_;
};

class ByteReader {
 public:
  ByteReader(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  explicit ByteReader(const Bytes& b) : ByteReader(b.data(), b.size()) {}

  std::uint8_t u8();
  std::uint16_t u16() {
    const std::uint8_t lo = u8();
    return static_cast<std::uint16_t>(lo | (u8() << 8));
  }
  std::uint32_t u32();
  std::uint64_t u64();
  float f32();
  std::uint64_t varint();
  std::int64_t svarint() {
    const std::uint64_t v = varint();
    return static_cast<std::int64_t>(v >> 1) ^ -static_cast<std::int64_t>(v & 1);
  }
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  std::size_t remaining() const { return n_ - pos_; }
  std::size_t position() const { return pos_; }
  // Marks the read as failed with `what` (the first failure is kept).
  void fail(const std::string& what);

 private:
  bool need(std::size_t k, const char* what);
  const std::uint8_t* p_;
  std::size_t n_;
  std::size_t pos_ = 0;
  std::string error_;
};

// CRC-32 (IEEE 802.3 polynomial) of a byte range, continuing from `crc`.
std::uint32_t crc32(const std::uint8_t* p, std::size_t n, std::uint32_t crc = 0);

}  // namespace slide::team
