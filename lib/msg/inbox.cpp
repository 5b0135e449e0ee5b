#include "msg/inbox.h"

#include <spdlog/spdlog.h>

namespace slide::msg {

const char* inboxDropName(InboxDrop d) {
  switch (d) {
    case InboxDrop::Oversize: return "oversize";
    case InboxDrop::Undecodable: return "undecodable";
    case InboxDrop::HandlerFailed: return "handler_failed";
    case InboxDrop::kCount: break;
  }
  return "?";
}

Inbox::Inbox(lcm::LCM& lcm, std::size_t max_bytes, double log_period_s)
    : lcm_(lcm),
      max_bytes_(max_bytes),
      log_period_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(log_period_s))) {}

Inbox::~Inbox() {
  for (lcm::Subscription* h : handles_)
    if (h) lcm_.unsubscribe(h);
}

void Inbox::add(const std::string& channel, Deliver deliver) {
  auto sub = std::make_unique<Sub>();
  sub->deliver = std::move(deliver);
  sub->inbox = this;
  sub->channel = channel;
  lcm::Subscription* handle = lcm_.subscribe(channel, &Sub::onRaw, sub.get());
  if (handle) handle->setQueueCapacity(kDefaultQueueCapacity);
  handles_.push_back(handle);
  subs_.push_back(std::move(sub));
}

void Inbox::setQueueCapacity(const std::string& channel, int capacity) {
  for (std::size_t i = 0; i < subs_.size(); ++i)
    if (subs_[i]->channel == channel && handles_[i]) handles_[i]->setQueueCapacity(capacity);
}

void Inbox::subscribeBytes(const std::string& channel, BytesHandler handler) {
  add(channel, [handler = std::move(handler)](const lcm::ReceiveBuffer* rb, const std::string& ch) {
    handler(ch, rb->data, rb->data_size);
    return true;
  });
}

void Inbox::unsubscribe(const std::string& channel) {
  for (std::size_t i = 0; i < subs_.size(); ++i)
    if (subs_[i]->channel == channel && handles_[i]) {
      lcm_.unsubscribe(handles_[i]);
      handles_[i] = nullptr;
    }
}

void Inbox::receive(Sub& sub, const lcm::ReceiveBuffer* rb, const std::string& channel) {
  if (rb->data_size > max_bytes_)
    return drop(sub, InboxDrop::Oversize, std::to_string(rb->data_size) + " bytes");
  try {
    if (!sub.deliver(rb, channel)) drop(sub, InboxDrop::Undecodable, std::to_string(rb->data_size) + " bytes");
  } catch (const std::exception& e) {
    drop(sub, InboxDrop::HandlerFailed, e.what());
  } catch (...) {
    drop(sub, InboxDrop::HandlerFailed, "unknown exception");
  }
}

void Inbox::countUndecodable(const std::string& channel, const std::string& why) {
  for (auto& s : subs_)
    if (s->channel == channel) return drop(*s, InboxDrop::Undecodable, why);
}

void Inbox::drop(Sub& sub, InboxDrop reason, const std::string& detail) {
  ++sub.drops[static_cast<int>(reason)];
  const auto now = std::chrono::steady_clock::now();
  std::uint64_t total = 0;
  for (std::uint64_t n : sub.drops) total += n;
  if (sub.logged == 0 || now - last_log_ >= log_period_) {
    spdlog::warn("{}: dropped a message ({}: {}); dropped so far: {}", sub.channel, inboxDropName(reason), detail,
                 summary());
    last_log_ = now;
    sub.logged = total;
  }
}

std::uint64_t Inbox::dropped(InboxDrop reason) const {
  std::uint64_t n = 0;
  for (const auto& s : subs_) n += s->drops[static_cast<int>(reason)];
  return n;
}

std::uint64_t Inbox::dropped() const {
  std::uint64_t n = 0;
  for (int r = 0; r < static_cast<int>(InboxDrop::kCount); ++r) n += dropped(static_cast<InboxDrop>(r));
  return n;
}

std::string Inbox::summary() const {
  std::string out;
  for (const auto& s : subs_) {
    std::string line;
    for (int r = 0; r < static_cast<int>(InboxDrop::kCount); ++r)
      if (s->drops[r])
        line += (line.empty() ? "" : ", ") + std::to_string(s->drops[r]) + " " + inboxDropName(static_cast<InboxDrop>(r));
    if (!line.empty()) out += (out.empty() ? "" : "; ") + s->channel + ": " + line;
  }
  return out;
}

std::vector<std::string> summaries(std::initializer_list<const Inbox*> inboxes) {
  std::vector<std::string> out;
  for (const Inbox* inbox : inboxes)
    if (inbox->dropped()) out.push_back(inbox->summary());
  return out;
}

}  // namespace slide::msg
