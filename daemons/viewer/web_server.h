#pragma once
// The viewer's web side over civetweb (Debian's libcivetweb-dev): the page's static files from
// one folder, GET /stats (JSON), and a WebSocket at /ws over which every browser gets the scene
// as deltas. Each browser has its own sender thread that, every `period_s`, asks `update` for
// what changed since its cursor and writes it; a browser that stops reading blocks only its own
// thread (civetweb's send timeout then ends it) and, having no queue, costs no memory: when it
// reads again it gets one delta covering what it missed. Browsers beyond `max_clients` are
// refused; requests larger than max_request_bytes, malformed or idle past request_timeout_ms
// are civetweb's to answer and close. Text frames from the browser (control commands, at most
// 4 KB) go to `control`.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

struct mg_context;
struct mg_connection;
namespace CLI {
class App;
}

namespace slide {

struct WebServerOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;
  std::string web_root;           // folder served as /
  int max_clients = 16;           // WebSocket browsers at once
  double period_s = 0.5;          // how often a browser is sent what changed
  int request_timeout_ms = 5000;  // idle or stalled connections end after this
  int max_request_bytes = 16384;  // request line and headers
};

// Adds --bind, --port, --web-root, --max-clients, --request-timeout-ms and --period to `app`.
void addWebServerOptions(CLI::App& app, WebServerOptions& opts);
// Throws naming what is missing when `web_root` has no index.html or no three.js (npm ci there).
void checkWebRoot(const std::string& web_root);

// Where a browser stands: the scene epoch and version it has, and when it last got a status.
struct ClientCursor {
  std::uint64_t epoch = 0, version = 0;
  double last_status_s = -1e9;
};

struct WebServerStats {
  std::uint64_t bytes_sent = 0, messages_sent = 0, clients_now = 0, clients_total = 0, clients_refused = 0,
                controls = 0, controls_refused = 0;
};

class WebServer {
 public:
  // What to send a browser at `cursor` (advanced by the callee); empty when nothing is due.
  using Update = std::function<std::string(ClientCursor& cursor)>;
  using Control = std::function<bool(const std::string& text)>;
  using Stats = std::function<std::string(const WebServerStats& own)>;  // the body of GET /stats

  // Starts listening; throws std::runtime_error naming the address when it cannot.
  WebServer(WebServerOptions opts, Update update, Control control, Stats stats);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  std::string url() const;
  WebServerStats stats() const;

 private:
  struct Client;
  static int onConnect(const mg_connection* conn, void* self);
  static void onReady(mg_connection* conn, void* self);
  static int onData(mg_connection* conn, int bits, char* data, std::size_t len, void* self);
  static void onClose(const mg_connection* conn, void* self);
  static int onStats(mg_connection* conn, void* self);
  void senderLoop(Client& c);

  WebServerOptions opts_;
  Update update_;
  Control control_;
  Stats stats_body_;
  mg_context* ctx_ = nullptr;
  mutable std::mutex mutex_;
  std::vector<std::shared_ptr<Client>> clients_;
  // Browsers admitted by onConnect whose handshake has not reached onReady yet: they hold a
  // slot, so that browsers connecting at once cannot all pass the max_clients check. A slot whose
  // handshake never completes is given back after request_timeout_ms.
  std::map<const mg_connection*, std::chrono::steady_clock::time_point> admitting_;
  WebServerStats stats_;
};

}  // namespace slide
