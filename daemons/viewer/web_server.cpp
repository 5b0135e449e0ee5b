#include "web_server.h"

#include <civetweb.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <stdexcept>
#include <thread>

namespace slide {

namespace {
constexpr std::size_t kMaxControlBytes = 4096;
}

void addWebServerOptions(CLI::App& app, WebServerOptions& web) {
  app.add_option("--bind", web.bind, "Address to serve on (127.0.0.1: this host only; tunnel with ssh -L)")
      ->capture_default_str();
  app.add_option("--port", web.port, "HTTP port")->capture_default_str()->check(CLI::Range(1, 65535));
  app.add_option("--web-root", web.web_root, "Folder with the page (index.html, viewer.js, node_modules/three)")
      ->capture_default_str();
  app.add_option("--max-clients", web.max_clients, "Browsers at once")->capture_default_str()->check(CLI::Range(1, 256));
  app.add_option("--request-timeout-ms", web.request_timeout_ms,
                 "A request not complete, or a browser not reading, for this long is dropped")
      ->capture_default_str()
      ->check(CLI::Range(100, 600000));
  app.add_option("--period", web.period_s, "Seconds between updates to a browser")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 10.0));
}

void checkWebRoot(const std::string& web_root) {
  const std::string three = web_root + "/node_modules/three/build/three.module.min.js";
  if (!std::filesystem::exists(web_root + "/index.html"))
    throw std::runtime_error("--web-root " + web_root + ": no index.html");
  if (!std::filesystem::exists(three))
    throw std::runtime_error(three + " missing: run ./slide setup (npm ci in " + web_root + ")");
}

struct WebServer::Client {
  mg_connection* conn = nullptr;
  std::thread thread;
  std::mutex m;
  std::condition_variable cv;
  bool closing = false;
};

WebServer::WebServer(WebServerOptions opts, Update update, Control control, Stats stats)
    : opts_(std::move(opts)), update_(std::move(update)), control_(std::move(control)), stats_body_(std::move(stats)) {
  mg_init_library(0);
  const std::string ports = opts_.bind + ":" + std::to_string(opts_.port);
  // Every WebSocket browser holds a civetweb worker thread; HTTP requests need a few more.
  const std::string threads = std::to_string(opts_.max_clients + 8);
  const std::string timeout = std::to_string(opts_.request_timeout_ms);
  const std::string max_request = std::to_string(opts_.max_request_bytes);
  const char* options[] = {"listening_ports", ports.c_str(),
                           "document_root", opts_.web_root.c_str(),
                           "num_threads", threads.c_str(),
                           "request_timeout_ms", timeout.c_str(),
                           "max_request_size", max_request.c_str(),
                           "enable_directory_listing", "no",
                           "enable_websocket_ping_pong", "yes",
                           "websocket_timeout_ms", "30000",
                           "static_file_max_age", "0",
                           nullptr};
  mg_callbacks callbacks{};
  callbacks.log_message = [](const mg_connection*, const char* message) {
    spdlog::debug("civetweb: {}", message);
    return 1;
  };
  ctx_ = mg_start(&callbacks, this, options);
  if (!ctx_) throw std::runtime_error("cannot serve HTTP on " + ports + " (port in use, or not an address of this host)");
  mg_set_request_handler(ctx_, "/stats", &WebServer::onStats, this);
  mg_set_websocket_handler(ctx_, "/ws", &WebServer::onConnect, &WebServer::onReady, &WebServer::onData,
                           &WebServer::onClose, this);
}

WebServer::~WebServer() {
  mg_stop(ctx_);  // closes every connection; onClose joins each sender
  mg_exit_library();
}

std::string WebServer::url() const {
  const std::string host = opts_.bind == "0.0.0.0" ? "127.0.0.1" : opts_.bind;
  return "http://" + host + ":" + std::to_string(opts_.port) + "/";
}

WebServerStats WebServer::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

int WebServer::onStats(mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  const std::string body = s->stats_body_ ? s->stats_body_(s->stats()) : "{}";
  mg_printf(conn,
            "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nCache-Control: no-store\r\nContent-Length: %zu\r\n"
            "Connection: close\r\n\r\n",
            body.size());
  mg_write(conn, body.data(), body.size());
  return 200;
}

int WebServer::onConnect(const mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(s->mutex_);
  for (auto it = s->admitting_.begin(); it != s->admitting_.end();)
    it = now - it->second > std::chrono::milliseconds(s->opts_.request_timeout_ms) ? s->admitting_.erase(it) : std::next(it);
  if (static_cast<int>(s->clients_.size() + s->admitting_.size()) >= s->opts_.max_clients) {
    ++s->stats_.clients_refused;
    spdlog::warn("refused a browser: already {} (--max-clients)", s->opts_.max_clients);
    return 1;
  }
  s->admitting_[conn] = now;
  return 0;
}

void WebServer::onReady(mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  auto c = std::make_shared<Client>();
  c->conn = conn;
  {
    std::lock_guard<std::mutex> lock(s->mutex_);
    s->admitting_.erase(conn);
    s->clients_.push_back(c);
    ++s->stats_.clients_total;
    s->stats_.clients_now = s->clients_.size();
  }
  mg_set_user_connection_data(conn, c.get());
  Client* raw = c.get();
  c->thread = std::thread([s, raw] { s->senderLoop(*raw); });
}

int WebServer::onData(mg_connection* conn, int bits, char* data, std::size_t len, void* self) {
  auto* s = static_cast<WebServer*>(self);
  const int opcode = bits & 0x0f;
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
  if (opcode != MG_WEBSOCKET_OPCODE_TEXT) return 1;  // pings are civetweb's; binary is ignored
  bool ok = len <= kMaxControlBytes && s->control_;
  if (ok) ok = s->control_(std::string(data, len));
  std::lock_guard<std::mutex> lock(s->mutex_);
  ++(ok ? s->stats_.controls : s->stats_.controls_refused);
  return 1;
}

void WebServer::onClose(const mg_connection* conn, void* self) {
  auto* s = static_cast<WebServer*>(self);
  auto* raw = static_cast<Client*>(mg_get_user_connection_data(conn));
  if (!raw) {  // refused or closed before it was ready
    std::lock_guard<std::mutex> lock(s->mutex_);
    s->admitting_.erase(conn);
    return;
  }
  std::shared_ptr<Client> c;
  {
    std::lock_guard<std::mutex> lock(s->mutex_);
    auto it = std::find_if(s->clients_.begin(), s->clients_.end(), [raw](const auto& p) { return p.get() == raw; });
    if (it == s->clients_.end()) return;
    c = *it;
    s->clients_.erase(it);
    s->stats_.clients_now = s->clients_.size();
  }
  {
    std::lock_guard<std::mutex> lock(c->m);
    c->closing = true;
  }
  c->cv.notify_all();
  if (c->thread.joinable()) c->thread.join();
}

void WebServer::senderLoop(Client& c) {
  ClientCursor cursor;
  const auto period = std::chrono::duration<double>(opts_.period_s);
  for (;;) {
    std::string out;
    try {
      out = update_(cursor);
    } catch (const std::exception& e) {
      spdlog::error("viewer update failed: {}", e.what());
    }
    if (!out.empty()) {
      const auto t0 = std::chrono::steady_clock::now();
      mg_lock_connection(c.conn);
      const int n = mg_websocket_write(c.conn, MG_WEBSOCKET_OPCODE_TEXT, out.data(), out.size());
      mg_unlock_connection(c.conn);
      if (n <= 0) {
        const double blocked = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (blocked * 1000.0 >= 0.9 * opts_.request_timeout_ms)
          spdlog::warn("a browser stopped reading: a send timed out after {:.1f} s; it is dropped", blocked);
        else
          spdlog::info("a browser went away (send failed)");
        break;
      }
      std::lock_guard<std::mutex> lock(mutex_);
      stats_.bytes_sent += out.size();
      ++stats_.messages_sent;
    }
    std::unique_lock<std::mutex> lock(c.m);
    if (c.cv.wait_for(lock, period, [&c] { return c.closing; })) break;
  }
}

}  // namespace slide
