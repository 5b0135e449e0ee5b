#pragma once
// Subscriptions that treat every datagram as hostile. A message is delivered to its handler
// only when it is at most `max_bytes` long and decodes to exactly its own size; the decoders
// lcm-gen writes are hardened at build time (cmake/lcm_gen_checked.cmake) so that no length
// field can make them throw, allocate more than the datagram holds or read past it. An
// exception out of a handler is caught too. Whatever fails is dropped, counted per channel
// and reason, and logged (the first at once, then a summary at most every `log_period_s`).
// Replaces LCM's typed `lcm.subscribe(channel, &Node::onX, &node)` in every daemon.
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <exception>
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

  explicit Inbox(lcm::LCM& lcm, std::size_t max_bytes = kDefaultMaxBytes, double log_period_s = 10.0);
  ~Inbox();
  Inbox(const Inbox&) = delete;
  Inbox& operator=(const Inbox&) = delete;

  // Typed: `handler` gets the decoded message, as with lcm::LCM::subscribe.
  template <class Msg, class Node>
  void subscribe(const std::string& channel,
                 void (Node::*handler)(const lcm::ReceiveBuffer*, const std::string&, const Msg*), Node* node) {
    add(channel, std::make_unique<Typed<Msg, Node>>(handler, node));
  }
  // Raw: for a handler that decodes itself (with the hardened decoders) or checks the bytes
  // first; the size cap and the exception guard still apply.
  template <class Node>
  void subscribeRaw(const std::string& channel, void (Node::*handler)(const lcm::ReceiveBuffer*, const std::string&),
                    Node* node) {
    add(channel, std::make_unique<Raw<Node>>(handler, node));
  }
  // Ends every subscription to `channel` (its counts stay).
  void unsubscribe(const std::string& channel);
  // A raw handler calls this for a message it found malformed, so that it is counted here.
  void countUndecodable(const std::string& channel, const std::string& why);

  std::uint64_t dropped() const;                      // all channels, all reasons
  std::uint64_t dropped(InboxDrop reason) const;      // all channels
  // "SCAN: 2 undecodable; PEER_MAP: 1 handler_failed"; empty when nothing was dropped.
  std::string summary() const;

 private:
  struct Sub {
    virtual ~Sub() = default;
    // Returns false when the message did not decode (counted as Undecodable).
    virtual bool deliver(const lcm::ReceiveBuffer* rb, const std::string& channel) = 0;
    Inbox* inbox = nullptr;
    std::string channel;
    std::uint64_t drops[static_cast<int>(InboxDrop::kCount)] = {};
    std::uint64_t logged = 0;  // drops already in a log line
    void onRaw(const lcm::ReceiveBuffer* rb, const std::string& ch) { inbox->receive(*this, rb, ch); }
  };
  template <class Msg, class Node>
  struct Typed : Sub {
    using Handler = void (Node::*)(const lcm::ReceiveBuffer*, const std::string&, const Msg*);
    Typed(Handler h, Node* n) : handler(h), node(n) {}
    bool deliver(const lcm::ReceiveBuffer* rb, const std::string& ch) override {
      Msg m;
      if (m.decode(rb->data, 0, static_cast<int>(rb->data_size)) != static_cast<int>(rb->data_size)) return false;
      (node->*handler)(rb, ch, &m);
      return true;
    }
    Handler handler;
    Node* node;
  };
  template <class Node>
  struct Raw : Sub {
    using Handler = void (Node::*)(const lcm::ReceiveBuffer*, const std::string&);
    Raw(Handler h, Node* n) : handler(h), node(n) {}
    bool deliver(const lcm::ReceiveBuffer* rb, const std::string& ch) override {
      (node->*handler)(rb, ch);
      return true;
    }
    Handler handler;
    Node* node;
  };

  void add(const std::string& channel, std::unique_ptr<Sub> sub);
  void receive(Sub& sub, const lcm::ReceiveBuffer* rb, const std::string& channel);
  void drop(Sub& sub, InboxDrop reason, const std::string& detail);

  lcm::LCM& lcm_;
  std::size_t max_bytes_;
  std::chrono::steady_clock::duration log_period_;
  std::chrono::steady_clock::time_point last_log_{};
  std::vector<std::unique_ptr<Sub>> subs_;
  std::vector<lcm::Subscription*> handles_;
};

}  // namespace slide::msg
