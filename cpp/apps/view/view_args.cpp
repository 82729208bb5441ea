#include "view_args.hpp"

#include <cmath>
#include <cstdlib>

#include "softsim/io/errors.hpp"

namespace softsim::view {

namespace {

double number(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v < 0)
    throw InputError("command line: " + flag + ": expected a number at or above 0, got \"" + text + "\"");
  return v;
}

}  // namespace

ViewArgs take_view_args(std::vector<std::string>& args) {
  ViewArgs v;
  for (const auto& a : args)
    if (a == "view") v.view = true;
  if (!v.view) return v;
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const bool takes = a == "--port" || a == "--host" || a == "--web" || a == "--record" || a == "--frames" ||
                       a == "--latency";
    if (!takes) {
      rest.push_back(a);
      continue;
    }
    if (i + 1 >= args.size()) throw InputError("command line: " + a + " expects a value");
    const std::string& value = args[++i];
    if (a == "--port") {
      const double p = number(a, value);
      if (p > 65535 || p != std::floor(p)) throw InputError("command line: --port: expected a port 0-65535");
      v.port = static_cast<int>(p);
    } else if (a == "--host") {
      v.host = value;
    } else if (a == "--web") {
      v.web_root = value;
    } else if (a == "--record") {
      v.record = value;
    } else if (a == "--frames") {
      const double f = number(a, value);
      if (f != std::floor(f)) throw InputError("command line: --frames: expected a whole number");
      v.frames = static_cast<long>(f);
    } else {
      v.latency = number(a, value);
      if (v.latency > 1) throw InputError("command line: --latency: expected at most 1 s");
    }
  }
  args = rest;
  return v;
}

}  // namespace softsim::view
