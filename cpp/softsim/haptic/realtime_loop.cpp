#include "softsim/haptic/realtime_loop.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <istream>
#include <ostream>
#include <string>

#include "softsim/io/errors.hpp"

namespace softsim::haptic {

namespace {

using Clock = std::chrono::steady_clock;

// One frame of the live loop: parse, step, format the answer into `answer`. False for a blank
// message (nothing to answer).
bool live_frame(HapticScene& scene, const char* message, const LineSource& where, double& last_t,
                HapticRecord& record, Clock::time_point received, char (&answer)[160], int& length) {
  double v[4];
  if (!parse_probe_line(message, where, v)) return false;
  if (record.frames > 0 && !(v[0] > last_t))
    throw InputError(where.name() + ": expected a time after " + std::to_string(last_t) + " s (times must increase)");
  last_t = v[0];
  const Eigen::Vector3d p(v[1], v[2], v[3]);
  const Eigen::Vector3d f = scene.frame(p);
  length = std::snprintf(answer, sizeof answer, "%.9g %.17g %.17g %.17g\n", v[0], f.x(), f.y(), f.z());
  record.push(v[0], p, f, scene.in_contact(), std::chrono::duration<double>(Clock::now() - received).count());
  return true;
}

class Socket {
 public:
  Socket() : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    if (fd_ < 0) throw InputError(std::string("udp: cannot open a socket: ") + std::strerror(errno));
  }
  ~Socket() { ::close(fd_); }
  Socket(const Socket&) = delete;
  Socket& operator=(const Socket&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

HapticRecord serve_lines(HapticScene& scene, std::istream& in, std::ostream& out, long max_frames,
                         VisualStream* visual) {
  HapticRecord record;
  if (max_frames > 0) record.reserve(max_frames);
  std::string line;
  const std::string prefix = "stdin:";
  LineSource where{prefix, 0};
  double last_t = 0;
  char answer[160];
  int length = 0;
  while ((max_frames == 0 || record.frames < max_frames) && std::getline(in, line)) {
    const auto received = Clock::now();
    ++where.number;
    if (!live_frame(scene, line.c_str(), where, last_t, record, received, answer, length)) continue;
    out.write(answer, length);
    out.flush();
    if (visual) visual->after_frame(record.frames, last_t, scene.displacement());
  }
  return record;
}

HapticRecord serve_udp(HapticScene& scene, int port, long max_frames, double idle_timeout,
                       const std::function<void(int port)>& on_listen, VisualStream* visual) {
  Socket sock;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::bind(sock.fd(), reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0)
    throw InputError("udp 127.0.0.1:" + std::to_string(port) + ": cannot bind: " + std::strerror(errno));
  socklen_t len = sizeof addr;
  ::getsockname(sock.fd(), reinterpret_cast<sockaddr*>(&addr), &len);
  const int bound = ntohs(addr.sin_port);
  const std::string name = "udp 127.0.0.1:" + std::to_string(bound);
  timeval tv{};
  tv.tv_sec = static_cast<long>(idle_timeout);
  tv.tv_usec = static_cast<long>((idle_timeout - tv.tv_sec) * 1e6);
  ::setsockopt(sock.fd(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  if (on_listen) on_listen(bound);

  HapticRecord record;
  if (max_frames > 0) record.reserve(max_frames);
  char buffer[512];
  char answer[160];
  int length = 0;
  double last_t = 0;
  const std::string prefix = name + ": datagram ";
  LineSource where{prefix, 0};
  while (max_frames == 0 || record.frames < max_frames) {
    sockaddr_in from{};
    socklen_t from_len = sizeof from;
    const ssize_t n = ::recvfrom(sock.fd(), buffer, sizeof buffer - 1, 0, reinterpret_cast<sockaddr*>(&from), &from_len);
    const auto received = Clock::now();
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK)
        throw InputError(name + ": no probe position for " + std::to_string(idle_timeout) +
                         " s after frame " + std::to_string(record.frames) +
                         ": the client stopped without sending \"end\"");
      if (errno == EINTR) continue;
      throw InputError(name + ": receive failed: " + std::strerror(errno));
    }
    ++where.number;
    std::size_t len = static_cast<std::size_t>(n);
    while (len > 0 && (buffer[len - 1] == '\n' || buffer[len - 1] == '\r')) --len;
    buffer[len] = '\0';
    if (std::strcmp(buffer, "end") == 0) break;
    if (!live_frame(scene, buffer, where, last_t, record, received, answer, length)) continue;
    ::sendto(sock.fd(), answer, static_cast<std::size_t>(length), 0, reinterpret_cast<sockaddr*>(&from), from_len);
    if (visual) visual->after_frame(record.frames, last_t, scene.displacement());
  }
  return record;
}

}  // namespace softsim::haptic
