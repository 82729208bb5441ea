#include "softsim/haptic/realtime_loop.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "softsim/haptic/wire_protocol.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::haptic {

namespace {

using Clock = std::chrono::steady_clock;

// Frames recorded before the record's arrays first grow: a long session grows them (amortised),
// a huge max_frames reserves no more than this.
constexpr long kReservedFrames = 1L << 16;
constexpr std::size_t kListedErrors = 20;
constexpr std::size_t kListedPeers = 10;
constexpr int kPollMilliseconds = 100;  // how soon a stop signal is seen while waiting

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

// SIGTERM, SIGINT and SIGHUP stop the session (the loop sees them within kPollMilliseconds, a
// blocked read or write returns EINTR); SIGPIPE is ignored so a reader that left is an EPIPE.
// The previous actions come back at the end of the session.
class StopSignals {
 public:
  StopSignals() {
    g_stop_signal = 0;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;  // no SA_RESTART: a blocked call returns
    for (int k = 0; k < 3; ++k) ::sigaction(kSignals[k], &sa, &old_[k]);
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGPIPE, &ignore, &old_pipe_);
  }
  ~StopSignals() {
    for (int k = 0; k < 3; ++k) ::sigaction(kSignals[k], &old_[k], nullptr);
    ::sigaction(SIGPIPE, &old_pipe_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  static int caught() { return g_stop_signal; }

 private:
  static constexpr int kSignals[3] = {SIGTERM, SIGINT, SIGHUP};
  struct sigaction old_[3] {};
  struct sigaction old_pipe_ {};
};

const char* signal_name(int sig) { return sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : "SIGHUP"; }

// What the session saw besides its frames, for the artifact's "session" member.
struct SessionLog {
  std::string transport, ended_by = "input_closed", peer;
  long messages = 0, comments = 0, errors = 0, oversized = 0, late_times = 0, other_peer_datagrams = 0;
  long undelivered = 0;  // frames computed whose answer could not be written (the reader left)
  long long kernel_dropped = 0;
  std::vector<std::string> error_messages, other_peers;
  int exit_code = 0;

  void error(const std::string& message) {
    ++errors;
    if (error_messages.size() < kListedErrors) error_messages.push_back(message);
  }
  void end(const std::string& why, int code) {
    ended_by = why;
    exit_code = code;
  }
  nlohmann::json payload(const VisualStream* visual) const {
    return {{"transport", transport},
            {"ended_by", ended_by},
            {"exit_code", exit_code},
            {"peer", peer.empty() ? nlohmann::json(nullptr) : nlohmann::json(peer)},
            {"messages", messages},
            {"comments", comments},
            {"errors", errors},
            {"error_messages", error_messages},
            {"oversized", oversized},
            {"time_gaps", late_times},
            {"undelivered_frames", undelivered},
            {"other_peer_datagrams", other_peer_datagrams},
            {"other_peers", other_peers},
            {"kernel_dropped", kernel_dropped},
            {"visual", visual ? visual->payload() : nlohmann::json(nullptr)}};
  }
};

// One message of a session, whatever the transport: parse, check, step, and the answer in
// `answer` (a force, "#", or an error). False when the message ends the session ("end").
class FrameServer {
 public:
  // `prefix` names a message in an error answer: "stdin:" or "datagram " and its number.
  FrameServer(HapticScene& scene, const ServeOptions& options, SessionLog& log, HapticRecord& record, const char* prefix)
      : scene_(scene), options_(options), log_(log), record_(record), prefix_(prefix) {}

  // `bytes`: the message's whole length (it may exceed the part kept in `message`).
  bool handle(std::string_view message, std::size_t bytes, Clock::time_point received) {
    ++log_.messages;
    if (bytes > kMaxLineBytes) {
      ++log_.oversized;
      return fail("expected a message of at most " + std::to_string(kMaxLineBytes) + " bytes, got " +
                             std::to_string(bytes) + " bytes starting " + excerpt(message));
    }
    parse_wire_line(message, line_);
    switch (line_.kind) {
      case WireLine::Kind::end:
        length_ = 0;
        return false;
      case WireLine::Kind::comment:
        ++log_.comments;
        answer_[0] = '#';
        answer_[1] = '\n';
        length_ = 2;
        return true;
      case WireLine::Kind::error:
        return fail(line_.error);
      case WireLine::Kind::frame:
        break;
    }
    if (record_.frames > 0 && !(line_.t > last_t_))
      return fail("expected a time after the previous frame's " + excerpt(last_t_text_) +
                             " (times must increase), got " + excerpt(line_.t_text));
    if (options_.workspace && !options_.workspace->contains(line_.position)) {
      char d[64];
      std::snprintf(d, sizeof d, "%.3g m", options_.workspace->distance(line_.position));
      char r[64];
      std::snprintf(r, sizeof r, "%.3g m", options_.workspace->reach());
      return fail(std::string("expected a tip position (metres) within ") + r +
                             " of the organ's bounding box, got one " + d + " away (millimetres sent as metres?)");
    }
    const double step = scene_.options().frame_step;
    if (record_.frames > 0 && line_.t - last_t_ > 1.5 * step) ++log_.late_times;
    last_t_ = line_.t;
    last_t_text_.assign(line_.t_text.begin(), line_.t_text.end());
    Eigen::Vector3d f = scene_.frame(line_.position);
    if (options_.limiter) f = options_.limiter->limit(record_.frames + 1, f);
    length_ = format_force_answer(answer_, sizeof answer_, line_.t_text, f);
    record_.push(line_.t, line_.position, f, scene_.in_contact(),
                 std::chrono::duration<double>(Clock::now() - received).count());
    frame_done_ = true;
    return true;
  }

  // A message refused before parsing (a datagram holding two lines).
  void refuse(const std::string& what) {
    ++log_.messages;
    fail(what);
  }

  const char* answer() const { return answer_; }
  std::size_t length() const { return length_; }
  // Whether the last message computed a frame (then the picture may follow the answer).
  bool take_frame() {
    const bool done = frame_done_;
    frame_done_ = false;
    return done;
  }
  double last_t() const { return last_t_; }

 private:
  bool fail(const std::string& what) {
    const std::string message = prefix_ + std::to_string(log_.messages) + ": " + what;
    log_.error(message);
    length_ = static_cast<std::size_t>(
        std::snprintf(answer_, sizeof answer_, "error %.*s\n", static_cast<int>(std::min<std::size_t>(message.size(), sizeof answer_ - 8)),
                      message.data()));
    length_ = std::min(length_, sizeof answer_ - 1);
    return true;
  }

  HapticScene& scene_;
  const ServeOptions& options_;
  SessionLog& log_;
  HapticRecord& record_;
  std::string prefix_;
  WireLine line_;
  double last_t_ = 0;
  std::string last_t_text_ = std::string(kMaxLineBytes, ' ');  // capacity reserved once
  char answer_[kMaxLineBytes + 256];
  std::size_t length_ = 0;
  bool frame_done_ = false;
};

// Lines of at most kMaxLineBytes from a descriptor; a longer line is kept to its start and its
// length counted. Waits in poll so a stop signal is seen.
class LineReader {
 public:
  explicit LineReader(int fd) : fd_(fd) {}
  enum class Status { line, closed, stopped };

  Status next() {
    length_ = 0;
    bytes_ = 0;
    while (true) {
      while (begin_ < end_) {
        const char c = buffer_[begin_++];
        if (c == '\n') return Status::line;
        if (length_ < kMaxLineBytes + 1) line_[length_++] = c;
        ++bytes_;
      }
      if (closed_) return bytes_ > 0 ? Status::line : Status::closed;  // a last line without its newline
      if (StopSignals::caught()) return Status::stopped;
      pollfd p{fd_, POLLIN, 0};
      const int ready = ::poll(&p, 1, kPollMilliseconds);
      if (ready < 0 && errno != EINTR) throw InputError(std::string("stdin: cannot wait for input: ") + std::strerror(errno));
      if (ready <= 0) continue;
      const ssize_t n = ::read(fd_, buffer_, sizeof buffer_);
      if (n < 0) {
        if (errno == EINTR || errno == EAGAIN) continue;
        throw InputError(std::string("stdin: read failed: ") + std::strerror(errno));
      }
      begin_ = 0;
      end_ = static_cast<std::size_t>(n);
      if (n == 0) closed_ = true;
    }
  }
  // The line without its newline (and a carriage return before it), cut at kMaxLineBytes + 1.
  std::string_view line() const {
    std::size_t n = length_;
    if (bytes_ <= kMaxLineBytes && n > 0 && line_[n - 1] == '\r') --n;
    return {line_, n};
  }
  // The line's whole length in bytes (a carriage return before the newline included).
  std::size_t bytes() const { return bytes_; }

 private:
  int fd_;
  char buffer_[1 << 16];
  std::size_t begin_ = 0, end_ = 0;
  bool closed_ = false;
  char line_[kMaxLineBytes + 1];
  std::size_t length_ = 0, bytes_ = 0;
};

// Writes all of `data`; false when the reader is gone (EPIPE) or a stop signal interrupts a
// write that a reader who stopped reading blocks.
bool write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) {
        if (StopSignals::caught()) return false;
        continue;
      }
      if (errno == EPIPE) return false;
      throw InputError(std::string("stdout: write failed: ") + std::strerror(errno));
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

void after_answer(FrameServer& server, const ServeOptions& o, const HapticRecord& record, HapticScene& scene) {
  if (o.visual && server.take_frame()) o.visual->after_frame(record.frames, server.last_t(), scene.displacement());
}

ServedSession finish(HapticRecord&& record, SessionLog& log, const ServeOptions& o) {
  if (StopSignals::caught()) log.end(signal_name(StopSignals::caught()), kExitStopped);
  record.reports["session"] = log.payload(o.visual);
  if (o.limiter) record.reports["device_safety"] = o.limiter->payload();
  ServedSession s{std::move(record), log.exit_code};
  return s;
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

std::string address(const sockaddr_in& a) {
  char ip[INET_ADDRSTRLEN] = "?";
  ::inet_ntop(AF_INET, &a.sin_addr, ip, sizeof ip);
  return std::string(ip) + ":" + std::to_string(ntohs(a.sin_port));
}

}  // namespace

ServedSession serve_lines(HapticScene& scene, int in_fd, int out_fd, const ServeOptions& o) {
  StopSignals signals;
  HapticRecord record;
  record.reserve(o.max_frames > 0 ? std::min(o.max_frames, kReservedFrames) : kReservedFrames);
  SessionLog log;
  log.transport = "stdin";
  FrameServer server(scene, o, log, record, "stdin:");
  LineReader reader(in_fd);
  while (o.max_frames == 0 || record.frames < o.max_frames) {
    if (StopSignals::caught()) break;  // lines already buffered are not served after a stop
    const LineReader::Status status = reader.next();
    const auto received = Clock::now();
    if (status == LineReader::Status::closed) break;
    if (status == LineReader::Status::stopped) break;
    if (!server.handle(reader.line(), reader.bytes(), received)) {
      log.end("end", 0);
      break;
    }
    if (!write_all(out_fd, server.answer(), server.length())) {
      if (server.take_frame()) ++log.undelivered;  // recorded, never felt
      if (!StopSignals::caught()) log.end("client_left", kExitClientLeft);
      break;
    }
    after_answer(server, o, record, scene);
  }
  if (o.max_frames > 0 && record.frames >= o.max_frames) log.end("max_frames", 0);
  return finish(std::move(record), log, o);
}

ServedSession serve_udp(HapticScene& scene, int port, const ServeOptions& o,
                        const std::function<void(int port)>& on_listen) {
  StopSignals signals;
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
  // The kernel counts the datagrams it dropped for a full receive queue (a flood): reported.
  const int on = 1;
  const bool counts_drops = ::setsockopt(sock.fd(), SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) == 0;
  if (on_listen) on_listen(bound);

  HapticRecord record;
  record.reserve(o.max_frames > 0 ? std::min(o.max_frames, kReservedFrames) : kReservedFrames);
  SessionLog log;
  log.transport = "udp";
  FrameServer server(scene, o, log, record, "datagram ");
  char buffer[kMaxLineBytes + 2];
  char control[CMSG_SPACE(sizeof(std::uint32_t))];
  sockaddr_in peer{};
  bool bound_peer = false;
  auto last_heard = Clock::now();
  while (o.max_frames == 0 || record.frames < o.max_frames) {
    if (StopSignals::caught()) break;
    const double silent = std::chrono::duration<double>(Clock::now() - last_heard).count();
    if (silent >= o.idle_timeout) {
      log.end("idle_timeout", kExitClientLeft);
      break;
    }
    pollfd p{sock.fd(), POLLIN, 0};
    const double wait_ms = std::min<double>(kPollMilliseconds, 1e3 * (o.idle_timeout - silent));
    const int ready = ::poll(&p, 1, std::max(1, static_cast<int>(wait_ms + 0.999)));
    if (ready < 0 && errno != EINTR) throw InputError(std::string("udp: cannot wait for a datagram: ") + std::strerror(errno));
    if (ready <= 0) continue;
    sockaddr_in from{};
    iovec iov{buffer, sizeof buffer};
    msghdr msg{};
    msg.msg_name = &from;
    msg.msg_namelen = sizeof from;
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    // MSG_TRUNC: the datagram's whole length even when it did not fit, so a cut one is refused.
    const ssize_t n = ::recvmsg(sock.fd(), &msg, MSG_TRUNC | MSG_DONTWAIT);
    const auto received = Clock::now();
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) continue;
      throw InputError("udp: receive failed: " + std::string(std::strerror(errno)));
    }
    if (counts_drops)
      for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
          std::uint32_t dropped = 0;
          std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
          log.kernel_dropped = dropped;
        }
    if (!bound_peer) {
      peer = from;
      bound_peer = true;
      log.peer = address(peer);
    } else if (from.sin_addr.s_addr != peer.sin_addr.s_addr || from.sin_port != peer.sin_port) {
      ++log.other_peer_datagrams;
      const std::string who = address(from);
      if (log.other_peers.size() < kListedPeers &&
          std::find(log.other_peers.begin(), log.other_peers.end(), who) == log.other_peers.end())
        log.other_peers.push_back(who);
      continue;
    }
    last_heard = received;
    const std::size_t bytes = static_cast<std::size_t>(n);
    std::size_t kept = std::min(bytes, sizeof buffer);
    if (bytes <= sizeof buffer)
      while (kept > 0 && (buffer[kept - 1] == '\n' || buffer[kept - 1] == '\r')) --kept;
    const std::size_t size = bytes <= sizeof buffer ? kept : bytes;
    std::string_view message(buffer, kept);
    // A newline inside a datagram would be a second message in one: refused whole.
    bool go_on = true;
    if (bytes <= kMaxLineBytes && message.find('\n') != std::string_view::npos)
      server.refuse("expected one line per datagram, got several in " + excerpt(message));
    else
      go_on = server.handle(message, size, received);
    if (!go_on) {
      log.end("end", 0);
      break;
    }
    ::sendto(sock.fd(), server.answer(), server.length(), 0, reinterpret_cast<sockaddr*>(&peer), sizeof peer);
    after_answer(server, o, record, scene);
  }
  if (o.max_frames > 0 && record.frames >= o.max_frames) log.end("max_frames", 0);
  return finish(std::move(record), log, o);
}

}  // namespace softsim::haptic
