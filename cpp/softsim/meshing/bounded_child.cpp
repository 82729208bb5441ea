#include "softsim/meshing/bounded_child.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "softsim/io/errors.hpp"
#include "softsim/io/limits.hpp"

namespace softsim::meshing {

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

// The child's answer: 'M' and the mesh (node count, tet count, coordinates, indices), 'C' and a
// config member's pointer, a NUL and its message (ConfigInputError), 'E' and an input error's
// message, or 'F' and another failure's message.
void send_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(3);
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

void send_message(int fd, char kind, const std::string& text) {
  send_all(fd, &kind, 1);
  send_all(fd, text.data(), text.size());
}

[[noreturn]] void child(int fd, const std::function<mesh::TetMesh()>& work) {
  ::alarm(static_cast<unsigned>(io::gmsh_timeout_seconds()));  // SIGALRM ends the child
  if (!kAddressSanitizer) {
    // ASan reserves terabytes of address space for its shadow memory: no limit under it.
    const rlim_t bytes = static_cast<rlim_t>(io::memory_limit_bytes());
    const rlimit limit{bytes, bytes};
    ::setrlimit(RLIMIT_AS, &limit);
  }
  try {
    const mesh::TetMesh m = work();
    const std::uint64_t counts[2] = {m.nodes.size(), m.tets.size()};
    const char kind = 'M';
    send_all(fd, &kind, 1);
    send_all(fd, counts, sizeof counts);
    if (!m.nodes.empty()) send_all(fd, m.nodes.data(), m.nodes.size() * sizeof(m.nodes[0]));
    if (!m.tets.empty()) send_all(fd, m.tets.data(), m.tets.size() * sizeof(m.tets[0]));
  } catch (const ConfigInputError& e) {
    send_message(fd, 'C', e.pointer + '\0' + e.what());
  } catch (const InputError& e) {
    send_message(fd, 'E', e.what());
  } catch (const std::bad_alloc&) {
    send_message(fd, 'F', "out of memory");
  } catch (const std::exception& e) {
    send_message(fd, 'F', e.what());
  }
  ::close(fd);
  ::_exit(0);  // none of the parent's exit handlers (its files, its sanitizer reports) run twice
}

std::string read_all(int fd) {
  std::string data;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
  }
  return data;
}

mesh::TetMesh decode_mesh(const std::string& data) {
  std::uint64_t counts[2];
  if (data.size() < 1 + sizeof counts) throw std::runtime_error("Gmsh child: truncated answer");
  std::memcpy(counts, data.data() + 1, sizeof counts);
  mesh::TetMesh m;
  const std::size_t node_bytes = counts[0] * sizeof(Eigen::Vector3d), tet_bytes = counts[1] * sizeof(mesh::Tet);
  if (data.size() != 1 + sizeof counts + node_bytes + tet_bytes) throw std::runtime_error("Gmsh child: truncated answer");
  m.nodes.resize(counts[0]);
  m.tets.resize(counts[1]);
  const char* p = data.data() + 1 + sizeof counts;
  if (node_bytes) std::memcpy(static_cast<void*>(m.nodes.data()), p, node_bytes);
  if (tet_bytes) std::memcpy(static_cast<void*>(m.tets.data()), p + node_bytes, tet_bytes);
  return m;
}

}  // namespace

mesh::TetMesh mesh_in_bounded_child(const std::function<mesh::TetMesh()>& work) {
  const double timeout = io::gmsh_timeout_seconds();  // read here: a bad value is the parent's error
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("Gmsh child: pipe: ") + std::strerror(errno));
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("Gmsh child: fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], work);
  }
  ::close(fds[1]);
  const std::string data = read_all(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status) || data.empty()) {
    char text[200];
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
      std::snprintf(text, sizeof text,
                    "expected a surface Gmsh fills within %.0f s (SOFTSIM_GMSH_TIMEOUT_S; a coarser target_edge "
                    "meshes faster), got no mesh after %.0f s", timeout, timeout);
    else if (WIFSIGNALED(status))
      std::snprintf(text, sizeof text, "expected a surface Gmsh can mesh, got Gmsh ending with signal %d%s",
                    WTERMSIG(status), kAddressSanitizer ? "" : " (out of memory under SOFTSIM_MEMORY_LIMIT_MB?)");
    else
      std::snprintf(text, sizeof text, "expected a surface Gmsh can mesh, got Gmsh ending with exit code %d and no mesh",
                    WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    throw ConfigInputError("/source", text);
  }
  if (data[0] == 'E') throw InputError(data.substr(1));
  if (data[0] == 'C') {
    const std::size_t nul = data.find('\0', 1);
    throw ConfigInputError(data.substr(1, nul - 1), data.substr(nul + 1));
  }
  if (data[0] == 'F') {
    if (data.substr(1) == "out of memory")
      throw ConfigInputError("/source/target_edge", "expected a mesh Gmsh makes within the memory limit "
                                                    "(SOFTSIM_MEMORY_LIMIT_MB), got Gmsh out of memory");
    throw std::runtime_error("Gmsh child: " + data.substr(1));
  }
  return decode_mesh(data);
}

}  // namespace softsim::meshing
