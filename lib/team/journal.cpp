#include "team/journal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace slide::team {
namespace {

constexpr std::uint8_t kMagic[4] = {'S', 'J', '1', '\n'};
constexpr std::size_t kHeader = 4 + 1 + 4, kTrailer = 4;

std::runtime_error sysError(const std::string& what, const std::string& path) {
  return std::runtime_error("journal " + path + ": " + what + ": " + std::strerror(errno));
}

std::uint32_t readU32(const std::uint8_t* p) {
  return p[0] | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) | (std::uint32_t(p[3]) << 24);
}

}  // namespace

Bytes Journal::frame(std::uint8_t type, const Bytes& payload) {
  Bytes rec(kHeader + payload.size() + kTrailer);
  std::memcpy(rec.data(), kMagic, 4);
  rec[4] = type;
  const auto len = static_cast<std::uint32_t>(payload.size());
  for (int i = 0; i < 4; ++i) rec[5 + i] = static_cast<std::uint8_t>(len >> (8 * i));
  if (!payload.empty()) std::memcpy(rec.data() + kHeader, payload.data(), payload.size());
  const std::uint32_t crc = crc32(rec.data() + 4, 5 + payload.size());
  for (int i = 0; i < 4; ++i) rec[kHeader + payload.size() + i] = static_cast<std::uint8_t>(crc >> (8 * i));
  return rec;
}

namespace {

Bytes readAll(const std::string& path) {
  Bytes file;
  std::ifstream in(path, std::ios::binary);
  if (in) file.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  else if (std::filesystem::exists(path)) throw std::runtime_error("journal " + path + ": cannot read");
  return file;
}

// The good records of `file` (appended to `records` when given); returns the end of the last.
std::size_t scan(const Bytes& file, std::vector<JournalRecord>* records, std::size_t* count) {
  std::size_t pos = 0;
  *count = 0;
  while (file.size() - pos >= kHeader + kTrailer) {
    const std::uint8_t* p = file.data() + pos;
    if (std::memcmp(p, kMagic, 4) != 0) break;
    const std::uint32_t len = readU32(p + 5);
    if (len > Journal::kMaxPayload || file.size() - pos < kHeader + len + kTrailer) break;
    if (crc32(p + 4, 5 + len) != readU32(p + kHeader + len)) break;
    if (records) records->push_back({p[4], Bytes(p + kHeader, p + kHeader + len)});
    pos += kHeader + len + kTrailer;
    ++*count;
  }
  return pos;
}

}  // namespace

std::vector<JournalRecord> Journal::read(const std::string& path, JournalRecovery* recovery) {
  const Bytes file = readAll(path);
  std::vector<JournalRecord> records;
  JournalRecovery info;
  info.good_bytes = scan(file, &records, &info.records);
  info.dropped_bytes = file.size() - info.good_bytes;
  if (recovery) *recovery = info;
  return records;
}

bool Journal::looksLikeJournal(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[4] = {};
  in.read(head, 4);
  return in.gcount() == 0 || std::memcmp(head, kMagic, static_cast<std::size_t>(in.gcount())) == 0;
}

Journal::Journal(const std::string& path, std::vector<JournalRecord>* records, JournalRecovery* recovery)
    : path_(path) {
  const Bytes file = readAll(path);
  JournalRecovery info;
  const std::size_t pos = scan(file, records, &info.records);
  info.good_bytes = pos;
  info.dropped_bytes = file.size() - pos;
  if (info.dropped_bytes > 0) {
    info.damaged_copy = path + ".damaged-" + std::to_string(pos);
    std::ofstream out(info.damaged_copy, std::ios::binary);
    out.write(reinterpret_cast<const char*>(file.data() + pos), static_cast<std::streamsize>(info.dropped_bytes));
    out.close();
    if (!out) {  // a damaged tail is no reason not to start: it is cut all the same
      info.not_saved = "cannot save it to " + info.damaged_copy + ": " + std::strerror(errno);
      std::remove(info.damaged_copy.c_str());
      info.damaged_copy.clear();
    }
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw sysError("cannot open for writing", path);
  if (::ftruncate(fd_, static_cast<off_t>(pos)) != 0) throw sysError("cannot cut damaged tail", path);
  if (::lseek(fd_, static_cast<off_t>(pos), SEEK_SET) < 0) throw sysError("cannot seek", path);
  size_ = pos;
  if (recovery) *recovery = info;
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(std::uint8_t type, const Bytes& payload, bool sync) {
  if (payload.size() > kMaxPayload) throw std::runtime_error("journal " + path_ + ": record too large");
  const Bytes rec = frame(type, payload);
  std::size_t done = 0;
  // A record torn by a failed write would hide every later one: cut it back off.
  auto fail = [&](const char* what) {
    const int err = errno;
    if (::ftruncate(fd_, static_cast<off_t>(size_)) == 0) ::lseek(fd_, static_cast<off_t>(size_), SEEK_SET);
    errno = err;
    return sysError(what, path_);
  };
  while (done < rec.size()) {
    const ssize_t n = ::write(fd_, rec.data() + done, rec.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw fail("write failed");
    }
    done += static_cast<std::size_t>(n);
  }
  if (sync && ::fdatasync(fd_) != 0) throw fail("fdatasync failed");
  size_ += rec.size();
}

std::size_t replayRecords(const std::vector<JournalRecord>& records,
                          const std::function<std::string(const JournalRecord&)>& apply, JournalRecovery& recovery) {
  std::size_t used = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    std::string why;
    try {
      why = apply(records[i]);
    } catch (const std::exception& e) {
      why = std::string("replay failed: ") + e.what();
    }
    if (why.empty()) {
      ++used;
      continue;
    }
    if (recovery.skipped++ == 0) recovery.first_skipped = "record " + std::to_string(i + 1) + ": " + why;
  }
  return used;
}

}  // namespace slide::team
