#include "team/team_keys.h"

#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace slide::team {
namespace {

std::string hex(const std::string& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned char c : bytes) {
    out += digits[c >> 4];
    out += digits[c & 15];
  }
  return out;
}

bool unhex(const std::string& text, std::string* out) {
  if (text.size() % 2) return false;
  out->clear();
  for (std::size_t i = 0; i < text.size(); i += 2) {
    int v = 0;
    for (int k = 0; k < 2; ++k) {
      const char c = text[i + k];
      const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
      if (d < 0) return false;
      v = v * 16 + d;
    }
    out->push_back(static_cast<char>(v));
  }
  return true;
}

}  // namespace

PairKeys loadTeamKeys(const std::string& path, std::int32_t robot) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw std::runtime_error("team key file " + path + ": cannot be read");
  if (st.st_mode & (S_IRWXG | S_IRWXO))
    throw std::runtime_error("team key file " + path + ": readable by other users (chmod 600 it)");
  std::ifstream in(path);
  if (!in) throw std::runtime_error("team key file " + path + ": cannot be read");
  PairKeys keys;
  bool owner = false;
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    const auto where = [&] { return "team key file " + path + ":" + std::to_string(lineno) + ": "; };
    std::istringstream ss(line);
    std::string word;
    if (!(ss >> word) || word[0] == '#') continue;
    std::int64_t id = -1;
    std::string key_hex, key, extra;
    if (word == "robot") {
      if (!(ss >> id) || ss >> extra) throw std::runtime_error(where() + "expected 'robot <id>'");
      if (id != robot)
        throw std::runtime_error(where() + "the keys of robot " + std::to_string(id) + ", not of robot " +
                                 std::to_string(robot));
      owner = true;
    } else if (word == "peer") {
      if (!(ss >> id >> key_hex) || ss >> extra || id < 0 || id > 32767)
        throw std::runtime_error(where() + "expected 'peer <id 0..32767> <hex key>'");
      if (!unhex(key_hex, &key) || key.size() < 16)
        throw std::runtime_error(where() + "the key of peer " + std::to_string(id) + " is not 32+ hex digits");
      if (id == robot) throw std::runtime_error(where() + "a key for the robot itself");
      if (!keys.emplace(static_cast<std::int32_t>(id), key).second)
        throw std::runtime_error(where() + "peer " + std::to_string(id) + " listed twice");
    } else {
      throw std::runtime_error(where() + "unknown line '" + word + "' (expected robot or peer)");
    }
  }
  if (!owner) throw std::runtime_error("team key file " + path + ": no 'robot <id>' line");
  return keys;
}

void writeTeamKeys(const std::string& path, std::int32_t robot, const PairKeys& keys) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f || ::chmod(tmp.c_str(), 0600) != 0) {
    if (f) std::fclose(f);
    throw std::runtime_error("cannot write team key file " + tmp);
  }
  std::string text = "# slide team keys: one key per pair of robots (keep this file on robot " +
                     std::to_string(robot) + " only)\nrobot " + std::to_string(robot) + "\n";
  for (const auto& [peer, key] : keys) text += "peer " + std::to_string(peer) + " " + hex(key) + "\n";
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot write team key file " + path);
}

std::string randomPairKey() {
  std::string key(32, '\0');
  if (RAND_bytes(reinterpret_cast<unsigned char*>(key.data()), static_cast<int>(key.size())) != 1)
    throw std::runtime_error("no random bytes for a team key (OpenSSL RAND_bytes failed)");
  return key;
}

std::string derivePairKey(const std::string& master, std::int32_t a, std::int32_t b) {
  if (master.empty()) throw std::invalid_argument("team master secret is empty");
  const std::string label = "slide-pair " + std::to_string(std::min(a, b)) + " " + std::to_string(std::max(a, b));
  unsigned char out[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (!HMAC(EVP_sha256(), master.data(), static_cast<int>(master.size()),
            reinterpret_cast<const unsigned char*>(label.data()), label.size(), out, &len))
    throw std::runtime_error("HMAC-SHA256 failed");
  return std::string(reinterpret_cast<char*>(out), len);
}

PairKeys derivePairKeys(const std::string& master, std::int32_t robot, const std::vector<std::int32_t>& team) {
  PairKeys keys;
  for (std::int32_t id : team)
    if (id != robot) keys[id] = derivePairKey(master, robot, id);
  return keys;
}

}  // namespace slide::team
