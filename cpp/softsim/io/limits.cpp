#include "softsim/io/limits.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::io {

namespace {

// A positive number of MiB from the environment, or `fallback` bytes when unset. A variable that
// is set but not a positive number is a bad command line, not a reason to ignore the limit.
std::uint64_t mib_from_env(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const double mib = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(mib > 0) || mib > 1e12)
    throw InputError(std::string("environment: ") + name + ": expected a positive number of MiB, got \"" + text + "\"");
  return static_cast<std::uint64_t>(mib * 1024.0 * 1024.0);
}

}  // namespace

std::uint64_t max_input_bytes() { return mib_from_env("SOFTSIM_MAX_INPUT_MB", 4096ull << 20); }

std::uint64_t memory_limit_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGESIZE);
  const std::uint64_t physical =
      pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : (16ull << 30);
  return mib_from_env("SOFTSIM_MEMORY_LIMIT_MB", physical / 10 * 8);
}

double max_element_updates() {
  const char* text = std::getenv("SOFTSIM_MAX_ELEMENT_UPDATES");
  if (!text || !*text) return 1e11;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v > 0) || !std::isfinite(v))
    throw InputError(std::string("environment: SOFTSIM_MAX_ELEMENT_UPDATES: expected a positive number, got \"") + text + "\"");
  return v;
}

double gmsh_timeout_seconds() {
  const char* text = std::getenv("SOFTSIM_GMSH_TIMEOUT_S");
  if (!text || !*text) return 600.0;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  // alarm() counts whole seconds, at most about 136 years of them in an unsigned.
  if (end == text || *end != '\0' || !(v >= 1) || !(v <= 1e9))
    throw InputError(std::string("environment: SOFTSIM_GMSH_TIMEOUT_S: expected a number of seconds from 1 to 1e9, got \"") +
                     text + "\"");
  return std::floor(v);
}

void require_work(const JsonReader& at, const std::string& key, double element_updates) {
  const double limit = max_element_updates();
  if (element_updates <= limit) return;
  char text[160];
  std::snprintf(text, sizeof text, "a run of at most %.3g element updates (SOFTSIM_MAX_ELEMENT_UPDATES; this one needs %.3g)",
                limit, element_updates);
  at.fail_member(key, text);
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  char out[64];
  std::snprintf(out, sizeof out, u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return out;
}

namespace {
std::string over_limit(double bytes, const std::string& what) {
  const auto limit = static_cast<double>(memory_limit_bytes());
  if (bytes <= limit) return "";
  return "a size whose run fits the memory limit: " + what + " would take about " + format_bytes(bytes) +
         ", the limit is " + format_bytes(limit) + " (SOFTSIM_MEMORY_LIMIT_MB)";
}
}  // namespace

void require_memory(const JsonReader& at, const std::string& key, double bytes, const std::string& what) {
  if (const std::string expected = over_limit(bytes, what); !expected.empty()) at.fail_member(key, expected);
}

void require_memory(const std::string& pointer, double bytes, const std::string& what) {
  if (const std::string expected = over_limit(bytes, what); !expected.empty())
    throw ConfigInputError(pointer, "expected " + expected);
}

}  // namespace softsim::io
