#include "io/lcm_log.h"

#include <stdexcept>

namespace slide::io {

namespace {
constexpr std::uint32_t kSync = 0xEDA1DA01u;
constexpr std::size_t kHeaderBytes = 4 + 8 + 8 + 4 + 4;

std::uint64_t bigEndian(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

void putBigEndian(std::vector<std::uint8_t>& out, std::uint64_t v, int n) {
  for (int i = n - 1; i >= 0; --i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
}  // namespace

LcmLogReader::LcmLogReader(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "rb")) {
  if (!f_) throw std::runtime_error(path + ": cannot open LCM log");
}

LcmLogReader::~LcmLogReader() {
  if (f_) std::fclose(f_);
}

long LcmLogReader::fileSize() {
  std::clearerr(f_);
  if (std::fseek(f_, 0, SEEK_END) != 0) return -1;
  return std::ftell(f_);
}

bool LcmLogReader::readAt(long offset, void* buf, std::size_t n) {
  std::clearerr(f_);
  if (std::fseek(f_, offset, SEEK_SET) != 0) return false;
  return std::fread(buf, 1, n, f_) == n;
}

bool LcmLogReader::next(LcmLogEvent& ev, const std::function<bool(const std::string&)>& wanted) {
  const long size = fileSize();
  while (size >= 0 && offset_ + static_cast<long>(kHeaderBytes) <= size) {
    std::uint8_t h[kHeaderBytes];
    if (!readAt(offset_, h, kHeaderBytes)) return false;
    const auto sync = static_cast<std::uint32_t>(bigEndian(h, 4));
    const auto channel_len = static_cast<std::int32_t>(bigEndian(h + 20, 4));
    const auto data_len = static_cast<std::int32_t>(bigEndian(h + 24, 4));
    if (sync != kSync || channel_len <= 0 || channel_len > kMaxChannelBytes || data_len < 0 || data_len > kMaxDataBytes) {
      // Not an event: move on byte by byte to the next sync word.
      ++counts_.corrupt;
      ++offset_;
      ++counts_.corrupt_bytes;
      std::uint8_t b[4];
      while (offset_ + 4 <= size && readAt(offset_, b, 4) && bigEndian(b, 4) != kSync) {
        ++offset_;
        ++counts_.corrupt_bytes;
      }
      continue;
    }
    const long end = offset_ + static_cast<long>(kHeaderBytes) + channel_len + data_len;
    if (end > size) return false;  // the tail is still being written
    std::string channel(static_cast<std::size_t>(channel_len), '\0');
    if (!readAt(offset_ + static_cast<long>(kHeaderBytes), channel.data(), channel.size())) return false;
    if (wanted && !wanted(channel)) {
      ++counts_.skipped;
      offset_ = end;
      continue;
    }
    ev.event_number = static_cast<std::int64_t>(bigEndian(h + 4, 8));
    ev.utime = static_cast<std::int64_t>(bigEndian(h + 12, 8));
    ev.channel = std::move(channel);
    ev.data.resize(static_cast<std::size_t>(data_len));
    if (data_len > 0 && std::fread(ev.data.data(), 1, ev.data.size(), f_) != ev.data.size()) return false;
    offset_ = end;
    ++counts_.events;
    return true;
  }
  return false;
}

bool writeLcmLogEvent(std::FILE* f, const LcmLogEvent& ev) {
  std::vector<std::uint8_t> out;
  out.reserve(kHeaderBytes + ev.channel.size() + ev.data.size());
  putBigEndian(out, kSync, 4);
  putBigEndian(out, static_cast<std::uint64_t>(ev.event_number), 8);
  putBigEndian(out, static_cast<std::uint64_t>(ev.utime), 8);
  putBigEndian(out, ev.channel.size(), 4);
  putBigEndian(out, ev.data.size(), 4);
  out.insert(out.end(), ev.channel.begin(), ev.channel.end());
  out.insert(out.end(), ev.data.begin(), ev.data.end());
  return std::fwrite(out.data(), 1, out.size(), f) == out.size() && std::fflush(f) == 0;
}

}  // namespace slide::io
