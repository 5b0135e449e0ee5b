#pragma once
// Subscriptions that treat every datagram as hostile. A message is delivered to its handler
// only when it is at most `max_bytes` long and decodes to exactly its own size; the decoders
// lcm-gen writes are hardened at build time (cmake/lcm_gen_checked.cmake) so that no length
// field can make them throw, allocate more than the datagram holds or read past it. An
// exception out of a handler is caught too. Whatever fails is dropped, counted per channel
// and reason, and logged (the first at once, then a summary at most every `log_period_s`).
// Replaces LCM's `lcm.subscribe(...)` in every daemon.
//
// LCM queues at most 30 received messages per subscription between two handle() calls and
// drops the rest without a word; a daemon busy for a while (a full solve, a burst of peer
// bundles after a link came back) lost observations that way. Every subscription here queues
// up to kDefaultQueueCapacity messages instead; a sensor stream whose frames may be skipped
// when the daemon falls behind (a scan or an image of a few MB) sets a smaller capacity.

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

namespace slide::msg {

enum class InboxDrop { Oversize, Undecodable, HandlerFailed, kCount };
const char* inboxDropName(InboxDrop d);

class Inbox {
 public:
  // Largest legitimate message on a slide bus: a full RGBD frame or LiDAR scan is a few MB.
  static constexpr std::size_t kDefaultMaxBytes = 64u << 20;
  // Messages queued per subscription while the daemon is busy (bundles, maps and closures are
  // a few KB: 10,000 hold a long link cut's burst of peer bundles in tens of MB).
  static constexpr int kDefaultQueueCapacity = 10000;

  explicit Inbox(lcm::LCM& lcm, std::size_t max_bytes = kDefaultMaxBytes, double log_period_s = 10.0);
  ~Inbox();
  Inbox(const Inbox&) = delete;
  Inbox& operator=(const Inbox&) = delete;

  // Typed: `handler` gets the decoded message, as with lcm::LCM::subscribe.
  template <class Msg, class Node>
  void subscribe(const std::string& channel,
                 void (Node::*handler)(const lcm::ReceiveBuffer*, const std::string&, const Msg*), Node* node) {
    add(channel, [handler, node](const lcm::ReceiveBuffer* rb, const std::string& ch) {
          Msg m;
          if (!decodes(rb, m)) return false;
          (node->*handler)(rb, ch, &m);
          return true;
        });
  }
  // Into functions, for a node that knows no LCM: `handler(channel, message)` gets the decoded
  // message; a bytes handler gets the raw bytes (for a node that decodes itself, with the
  // hardened decoders, or checks the bytes first) and reports what it finds malformed through
  // countUndecodable or its own counts.
  template <class Msg>
  void subscribe(const std::string& channel, std::function<void(const std::string&, const Msg&)> handler) {
    add(channel, [handler = std::move(handler)](const lcm::ReceiveBuffer* rb, const std::string& ch) {
          Msg m;
          if (!decodes(rb, m)) return false;
          handler(ch, m);
          return true;
        });
  }
  using BytesHandler = std::function<void(const std::string& channel, const void* data, std::size_t size)>;
  void subscribeBytes(const std::string& channel, BytesHandler handler);
  // Ends every subscription to `channel` (its counts stay).
  void unsubscribe(const std::string& channel);
  // At most `capacity` messages of `channel` wait for the daemon; older ones beyond it are
  // dropped by LCM (for sensor frames a lagging daemon must skip). Applies to the channel's
  // current subscriptions.
  void setQueueCapacity(const std::string& channel, int capacity);
  // A bytes handler calls this for a message it found malformed, so that it is counted here.
  void countUndecodable(const std::string& channel, const std::string& why);

  std::uint64_t dropped() const;                      // all channels, all reasons
  std::uint64_t dropped(InboxDrop reason) const;      // all channels
  // "SCAN: 2 undecodable; PEER_MAP: 1 handler_failed"; empty when nothing was dropped.
  std::string summary() const;

 private:
  // Hands a datagram to its handler; false when the message did not decode (counted as Undecodable).
  using Deliver = std::function<bool(const lcm::ReceiveBuffer*, const std::string&)>;
  struct Sub {
    Deliver deliver;
    Inbox* inbox = nullptr;
    std::string channel;
    std::uint64_t drops[static_cast<int>(InboxDrop::kCount)] = {};
    std::uint64_t logged = 0;  // drops already in a log line
    void onRaw(const lcm::ReceiveBuffer* rb, const std::string& ch) { inbox->receive(*this, rb, ch); }
  };
  template <class Msg>
  static bool decodes(const lcm::ReceiveBuffer* rb, Msg& m) {
    return m.decode(rb->data, 0, static_cast<int>(rb->data_size)) == static_cast<int>(rb->data_size);
  }

  void add(const std::string& channel, Deliver deliver);
  void receive(Sub& sub, const lcm::ReceiveBuffer* rb, const std::string& channel);
  void drop(Sub& sub, InboxDrop reason, const std::string& detail);

  lcm::LCM& lcm_;
  std::size_t max_bytes_;
  std::chrono::steady_clock::duration log_period_;
  std::chrono::steady_clock::time_point last_log_{};
  std::vector<std::unique_ptr<Sub>> subs_;
  std::vector<lcm::Subscription*> handles_;
};

// The summary() of each of `inboxes` that dropped something.
std::vector<std::string> summaries(std::initializer_list<const Inbox*> inboxes);

}  // namespace slide::msg
