// A minimal device bridge for haptic_sim view (protocol softsim-view 1, cpp/apps/haptic_sim.md,
// "The live scene in a browser"): what a CHAI3D or OpenHaptics servo loop does with its device,
// here with tip positions read from stdin. It connects to ws://HOST:PORT/, sends each line
// "t x y z" (s, m) as a sample at its time t on its own clock, prints each state's force as
// "t fx fy fz" (the scene's time, N) on stdout, and ends with "stop" (or just closes: --leave).
//   view_bridge --port N [--host 127.0.0.1] [--hold S] [--leave] < trajectory.txt
// A device loop would call send_sample() from its servo callback and render the last force.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

struct Sample {
  double t, x, y, z;
};

class Bridge {
 public:
  Bridge(asio::io_context& io, std::vector<Sample> samples, double hold, bool leave)
      : ws_(io), timer_(io), samples_(std::move(samples)), hold_(hold), leave_(leave) {}

  void connect(const std::string& host, const std::string& port) {
    tcp::resolver resolver(ws_.get_executor());
    asio::connect(ws_.next_layer(), resolver.resolve(host, port));
    ws_.handshake(host + ":" + port, "/");
    send(R"({"type": "hello", "protocol": 1})");
    start_ = std::chrono::steady_clock::now();
    read();
    next();
  }

 private:
  void read() {
    ws_.async_read(buffer_, [this](beast::error_code ec, std::size_t) {
      if (ec) return;  // closed: the scene ended the session
      if (ws_.got_text()) print(beast::buffers_to_string(buffer_.data()));
      buffer_.consume(buffer_.size());
      read();
    });
  }

  // The state's "t" and "force", without a JSON library: the fields are fixed by the protocol.
  static void print(const std::string& m) {
    if (m.find("\"type\":\"error\"") != std::string::npos) {
      std::cerr << "view_bridge: " << m << "\n";
      return;
    }
    if (m.find("\"type\":\"state\"") == std::string::npos) return;
    const auto field = [&](const char* key) { return m.find(key); };
    const std::size_t f = field("\"force\":["), t = field("\"t\":");
    if (f == std::string::npos || t == std::string::npos) return;
    double fx, fy, fz;
    if (std::sscanf(m.c_str() + f + 9, "%lf,%lf,%lf", &fx, &fy, &fz) != 3) return;
    std::printf("%.9g %.17g %.17g %.17g\n", std::atof(m.c_str() + t + 4), fx, fy, fz);
  }

  void next() {
    using namespace std::chrono;
    if (k_ == samples_.size()) {
      // Held at the last sample for `hold` seconds, then the session ends.
      timer_.expires_at(start_ + duration_cast<steady_clock::duration>(duration<double>(samples_.back().t + hold_)));
      timer_.async_wait([this](beast::error_code) {
        if (!leave_) send(R"({"type": "stop"})");
        else ws_.async_close(websocket::close_code::normal, [](beast::error_code) {});
      });
      return;
    }
    const Sample& s = samples_[k_];
    timer_.expires_at(start_ + duration_cast<steady_clock::duration>(duration<double>(s.t)));
    timer_.async_wait([this, s](beast::error_code ec) {
      if (ec) return;
      char line[256];
      std::snprintf(line, sizeof line, R"({"type": "sample", "t": %.17g, "p": [%.17g, %.17g, %.17g]})", s.t, s.x,
                    s.y, s.z);
      send(line);
      ++k_;
      next();
    });
  }

  void send(std::string text) {
    queue_.push_back(std::move(text));
    if (queue_.size() == 1) write();
  }
  void write() {
    ws_.async_write(asio::buffer(queue_.front()), [this](beast::error_code ec, std::size_t) {
      if (ec) return;
      queue_.erase(queue_.begin());
      if (!queue_.empty()) write();
    });
  }

  websocket::stream<tcp::socket> ws_;
  asio::steady_timer timer_;
  beast::flat_buffer buffer_;
  std::vector<Sample> samples_;
  std::vector<std::string> queue_;
  std::size_t k_ = 0;
  double hold_;
  bool leave_;
  std::chrono::steady_clock::time_point start_;
};

int main(int argc, char** argv) {
  std::string host = "127.0.0.1", port;
  double hold = 0.2;
  bool leave = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--port" && i + 1 < argc) port = argv[++i];
    else if (a == "--host" && i + 1 < argc) host = argv[++i];
    else if (a == "--hold" && i + 1 < argc) hold = std::atof(argv[++i]);
    else if (a == "--leave") leave = true;
    else {
      std::cerr << "usage: view_bridge --port N [--host 127.0.0.1] [--hold S] [--leave] < lines \"t x y z\"\n";
      return 2;
    }
  }
  if (port.empty()) {
    std::cerr << "view_bridge: error: --port N is required\n";
    return 2;
  }
  std::vector<Sample> samples;
  std::string line;
  for (long n = 1; std::getline(std::cin, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    Sample s{};
    if (!(in >> s.t >> s.x >> s.y >> s.z) || (!samples.empty() && !(s.t > samples.back().t))) {
      std::cerr << "view_bridge: error: stdin:" << n << ": expected \"t x y z\" with t increasing\n";
      return 2;
    }
    samples.push_back(s);
  }
  if (samples.empty()) {
    std::cerr << "view_bridge: error: stdin: expected at least one line \"t x y z\"\n";
    return 2;
  }
  try {
    asio::io_context io;
    Bridge bridge(io, std::move(samples), hold, leave);
    bridge.connect(host, port);
    io.run();
  } catch (const std::exception& e) {
    std::cerr << "view_bridge: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
