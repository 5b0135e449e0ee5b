// slide-viewer's web side under abuse, as a process on loopback: malformed, oversized and
// never-finished requests, more browsers than allowed, and a browser that stops reading while
// big maps stream in. Through all of it the page is still served and a well-behaved browser
// keeps getting updates; the viewer exits cleanly at the end.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "viewer_log_fixture.h"
#include "viewer_process.h"

using namespace slide;
using namespace slide::viewer_test;
namespace fs = std::filesystem;

namespace {
// `n` objects in a row, shifted by `dx` (so that every map is all new).
object_map_t bigMap(int n, double dx) {
  std::vector<Object> objs;
  for (int i = 0; i < n; ++i) objs.push_back(bush(i, dx + 0.5 * (i % 200), 0.5 * (i / 200)));
  return mapMsg(0, objs);
}
}  // namespace

TEST(ViewerHttp, StaysUpUnderMalformedOversizedManyAndStalledClients) {
  const fs::path dir = fs::path(SLIDE_BINARY_DIR) / "tests/viewer/http";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string log = (dir / "robot0.lcmlog").string();
  const std::int64_t t0 = 1700000000000000LL;
  {
    LogWriter w(log);
    writeRobotRun(w, t0);
  }
  const int port = freePort();
  ViewerProcess viewer({"--replay", log, "--follow", "--port", std::to_string(port), "--max-clients", "4",
                        "--request-timeout-ms", "1500", "--period", "0.1"},
                       (dir / "viewer.log").string(), port);
  ASSERT_TRUE(viewer.alive()) << "slide-viewer did not start: " << (dir / "viewer.log");
  EXPECT_EQ(get(port, "/").rfind("HTTP/1.1 200", 0), 0u);

  // Malformed and hostile requests: answered with an error or closed, never served.
  EXPECT_EQ(exchange(port, "THIS IS NOT HTTP\r\n\r\n", 3).find("200 OK"), std::string::npos);
  EXPECT_EQ(exchange(port, std::string(70000, '\x01'), 3).find("200 OK"), std::string::npos);
  const std::string huge = "GET / HTTP/1.1\r\nHost: x\r\nX-Big: " + std::string(200000, 'a') + "\r\n\r\n";
  EXPECT_EQ(exchange(port, huge, 3).find("200 OK"), std::string::npos);
  EXPECT_EQ(get(port, "/../../../../etc/passwd").find("root:"), std::string::npos);
  EXPECT_EQ(get(port, "/%2e%2e/%2e%2e/%2e%2e/etc/passwd").find("root:"), std::string::npos);
  EXPECT_EQ(exchange(port, "POST /ws HTTP/1.1\r\nHost: x\r\nContent-Length: 99999999999\r\n\r\nabc", 3).find("200 OK"),
            std::string::npos);
  // Connections that never finish their request hold no thread for ever.
  std::vector<int> idle;
  for (int i = 0; i < 20; ++i) {
    const int fd = connectLocal(port);
    if (fd >= 0) sendAll(fd, "GET / HTTP/1.1\r\nHost:");
    idle.push_back(fd);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  EXPECT_EQ(get(port, "/index.html", 5).rfind("HTTP/1.1 200", 0), 0u) << "page not served after 20 idle connections";
  for (int fd : idle)
    if (fd >= 0) close(fd);

  // More browsers than --max-clients: the extra ones are refused, the first four served.
  std::vector<int> socks;
  for (int i = 0; i < 8; ++i) socks.push_back(openSocket(port));
  int accepted = 0;
  for (int fd : socks) accepted += fd >= 0;
  EXPECT_EQ(accepted, 4);
  for (int fd : socks)
    if (fd >= 0) close(fd);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));

  // A browser that stops reading (tiny receive buffer, never reads) while 40 maps of 12000
  // objects (~0.6 MB a delta: more than the kernel buffers hold) stream in; a second browser
  // keeps reading. The stalled one's sends time out and it is dropped.
  const int stalled = openSocket(port, 4096);
  ASSERT_GE(stalled, 0);
  const int reader = openSocket(port);
  ASSERT_GE(reader, 0);
  std::string got;
  {
    LogWriter w(log, "ab");
    for (int k = 0; k < 40; ++k) {
      w.write("OBJECT_MAP", bigMap(12000, k), t0 + 1000000 + k * 100000);
      got += readAll(reader, 0.15);
    }
  }
  got += readAll(reader, 3.0);
  // The last map's last object (id 11999 at x 39 + 99.5, y 29.5) reached the reading browser.
  EXPECT_NE(got.find("[11999,0.0,2.0,138.5,29.5,"), std::string::npos)
      << "the reading browser was held up by the stalled one (" << got.size() << " bytes received)";
  const auto t_page = std::chrono::steady_clock::now();
  EXPECT_EQ(get(port, "/", 5).rfind("HTTP/1.1 200", 0), 0u);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t_page).count(), 2.0);
  const std::string stats = get(port, "/stats");
  EXPECT_NE(stats.find("\"clients_refused\":4"), std::string::npos) << stats;
  close(stalled);
  close(reader);
  EXPECT_TRUE(viewer.alive());
  EXPECT_EQ(viewer.stop(), 0) << "slide-viewer did not exit cleanly on SIGTERM";
  std::ifstream in(dir / "viewer.log");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("a browser stopped reading: a send timed out"), std::string::npos) << "the stalled browser was never dropped";
}
