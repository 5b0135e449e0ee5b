#pragma once
// A slide-viewer child process and plain-socket HTTP for the viewer's process tests (loopback
// only): a free port, start and stop, GET with a timeout.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace slide::viewer_test {

// A port nothing listens on now (bound to 0 and released).
inline int freePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  close(fd);
  return ntohs(a.sin_port);
}

// A connected socket to 127.0.0.1:port, or -1.
inline int connectLocal(int port, int rcvbuf = 0) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (rcvbuf > 0) setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

inline bool sendAll(int fd, const std::string& s) {
  std::size_t off = 0;
  while (off < s.size()) {
    const ssize_t n = send(fd, s.data() + off, s.size() - off, MSG_NOSIGNAL);
    if (n <= 0) return false;
    off += static_cast<std::size_t>(n);
  }
  return true;
}

// Everything the peer sends until it closes or `timeout_s` passes.
inline std::string readAll(int fd, double timeout_s) {
  std::string out;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  char buf[65536];
  while (std::chrono::steady_clock::now() < end) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
  }
  return out;
}

// The raw response to `request` ("" when nothing came back within `timeout_s`).
inline std::string exchange(int port, const std::string& request, double timeout_s = 5.0) {
  const int fd = connectLocal(port);
  if (fd < 0) return "";
  sendAll(fd, request);
  std::string out = readAll(fd, timeout_s);
  close(fd);
  return out;
}

inline std::string get(int port, const std::string& path, double timeout_s = 5.0) {
  return exchange(port, "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n", timeout_s);
}

inline const std::string kUpgrade =
    "GET /ws HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
    "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";

// A WebSocket client: the handshake done, or fd -1.
inline int openSocket(int port, int rcvbuf = 0) {
  const int fd = connectLocal(port, rcvbuf);
  if (fd < 0) return -1;
  sendAll(fd, kUpgrade);
  char buf[512];
  pollfd p{fd, POLLIN, 0};
  if (poll(&p, 1, 3000) <= 0) {
    close(fd);
    return -1;
  }
  const ssize_t n = recv(fd, buf, 12, 0);  // "HTTP/1.1 101" only: the frames stay in the socket
  if (n < 12 || std::string(buf, 12) != "HTTP/1.1 101") {
    close(fd);
    return -1;
  }
  return fd;
}

class ViewerProcess {
 public:
  // Starts build/bin/slide-viewer with `args` (stderr into `log`); waits until it serves GET /.
  ViewerProcess(const std::vector<std::string>& args, const std::string& log, int port) : port_(port) {
    pid_ = fork();
    if (pid_ == 0) {
      if (!std::freopen(log.c_str(), "w", stderr)) _exit(126);
      std::vector<std::string> all{std::string(SLIDE_BINARY_DIR) + "/bin/slide-viewer"};
      all.insert(all.end(), args.begin(), args.end());
      std::vector<char*> argv;
      for (auto& a : all) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
    for (int i = 0; i < 200 && alive(); ++i) {
      if (get(port_, "/", 1.0).rfind("HTTP/1.1 200", 0) == 0) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  ~ViewerProcess() { stop(); }
  bool alive() { return pid_ > 0 && waitpid(pid_, nullptr, WNOHANG) == 0; }
  // SIGTERM; the exit status (-1 when it was gone already).
  int stop() {
    if (pid_ <= 0) return -1;
    kill(pid_, SIGTERM);
    int status = -1;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return status;
  }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }

 private:
  pid_t pid_ = -1;
  int port_;
};

}  // namespace slide::viewer_test
