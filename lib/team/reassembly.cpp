#include "team/reassembly.h"

namespace slide::team {

std::vector<Bytes> splitPayload(const Bytes& data, std::size_t max_chunk) {
  std::vector<Bytes> out;
  for (std::size_t pos = 0; pos < data.size(); pos += max_chunk)
    out.emplace_back(data.begin() + static_cast<std::ptrdiff_t>(pos),
                     data.begin() + static_cast<std::ptrdiff_t>(std::min(data.size(), pos + max_chunk)));
  if (out.empty()) out.emplace_back();
  return out;
}

void Reassembler::erase(std::map<Key, Partial>::iterator it) {
  bytes_ -= it->second.bytes;
  auto s = by_sender_.find(it->second.sender);
  if ((s->second -= it->second.bytes) == 0) by_sender_.erase(s);
  partial_.erase(it);
}

std::optional<Bytes> Reassembler::add(const Chunk& c, Micros now, std::optional<Drop>* drop) {
  if (c.num_chunks == 1) return c.data;
  const Key key{static_cast<int>(c.kind), c.origin, c.seq, c.num_chunks};
  auto it = partial_.find(key);
  if (it == partial_.end()) {
    // What a partial payload costs is its slots as much as its bytes: a chunk claiming 32,767
    // parts allocates 32,767 slots.
    const std::size_t slots = static_cast<std::size_t>(c.num_chunks) * kSlotBytes;
    // No sender takes more than half the space: one cannot starve the others' maps.
    if (bytes_ + slots + c.data.size() > max_bytes_ || by_sender_[c.sender] + slots + c.data.size() > max_bytes_ / 2) {
      *drop = Drop::Overflow;
      return std::nullopt;
    }
    Partial p;
    p.parts.resize(static_cast<std::size_t>(c.num_chunks));
    p.have.assign(static_cast<std::size_t>(c.num_chunks), false);
    p.started = now;
    p.bytes = slots;
    p.sender = c.sender;
    bytes_ += slots;
    by_sender_[c.sender] += slots;
    it = partial_.emplace(key, std::move(p)).first;
  }
  Partial& p = it->second;
  const auto i = static_cast<std::size_t>(c.chunk_index);
  if (p.have[i]) {
    if (p.parts[i] != c.data) *drop = Drop::Malformed;  // same slot, different bytes
    else *drop = Drop::Duplicate;
    return std::nullopt;
  }
  if (bytes_ + c.data.size() > max_bytes_ || by_sender_[p.sender] + c.data.size() > max_bytes_ / 2) {
    *drop = Drop::Overflow;
    return std::nullopt;
  }
  p.parts[i] = c.data;
  p.have[i] = true;
  p.bytes += c.data.size();
  bytes_ += c.data.size();
  by_sender_[p.sender] += c.data.size();
  if (++p.count < c.num_chunks) return std::nullopt;
  Bytes whole;
  for (const auto& part : p.parts) whole.insert(whole.end(), part.begin(), part.end());
  erase(it);
  return whole;
}

void Reassembler::expire(Micros now) {
  for (auto it = partial_.begin(); it != partial_.end();) {
    auto next = std::next(it);
    if (now - it->second.started > timeout_) erase(it);
    it = next;
  }
}

}  // namespace slide::team
