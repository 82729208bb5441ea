#include "softsim/haptic/view_protocol.hpp"

#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

namespace softsim::haptic {

namespace {

using nlohmann::json;

bool read_vector(const json& j, const char* key, Eigen::Vector3d& v, std::string& error) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_array() || it->size() != 3) {
    error = std::string("/") + key + ": expected an array of 3 numbers";
    return false;
  }
  for (int d = 0; d < 3; ++d) {
    const json& x = (*it)[d];
    if (!x.is_number() || !std::isfinite(x.get<double>())) {
      error = std::string("/") + key + "/" + std::to_string(d) + ": expected a finite number";
      return false;
    }
    v[d] = x.get<double>();
  }
  return true;
}

json array3(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

ClientMessage parse_client_message(const std::string& text, double last_t, bool has_last, double max_edge) {
  ClientMessage m;
  if (text.size() > kViewMaxMessage) {
    m.error = "expected a message of at most " + std::to_string(kViewMaxMessage) + " bytes";
    return m;
  }
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) {
    m.error = "expected a JSON object";
    return m;
  }
  const auto type = j.find("type");
  if (type == j.end() || !type->is_string()) {
    m.error = "/type: expected \"hello\", \"sample\", \"next\" or \"stop\"";
    return m;
  }
  const std::string& kind = type->get_ref<const std::string&>();
  if (kind == "hello") {
    const auto p = j.find("protocol");
    if (p != j.end() && !(p->is_number_integer() && p->get<int>() == kViewProtocol)) {
      m.error = "/protocol: expected " + std::to_string(kViewProtocol) + " (softsim-view)";
      return m;
    }
    const auto states = j.find("states");
    if (states != j.end()) {
      if (!states->is_string() || (*states != "push" && *states != "pull")) {
        m.error = "/states: expected \"push\" or \"pull\"";
        return m;
      }
      m.pull = *states == "pull";
    }
    m.kind = ClientMessage::Kind::hello;
  } else if (kind == "next") {
    m.kind = ClientMessage::Kind::next;
  } else if (kind == "stop") {
    m.kind = ClientMessage::Kind::stop;
  } else if (kind == "sample") {
    const auto t = j.find("t");
    if (t == j.end() || !t->is_number() || !std::isfinite(t->get<double>())) {
      m.error = "/t: expected a finite time (s)";
      return m;
    }
    m.sample.t = t->get<double>();
    if (has_last && !(m.sample.t > last_t)) {
      m.error = "/t: expected a time after " + std::to_string(last_t) + " s (times must increase)";
      return m;
    }
    if (!read_vector(j, "p", m.sample.position, m.error)) return m;
    const auto blade = j.find("blade");
    if (blade != j.end()) {
      if (!blade->is_boolean()) {
        m.error = "/blade: expected true or false";
        return m;
      }
      m.sample.blade = blade->get<bool>();
    }
    if (m.sample.blade) {
      if (!read_vector(j, "edge", m.sample.edge, m.error)) return m;
      const double length = m.sample.edge.norm();
      if (!(length > 0 && length <= max_edge)) {
        m.error = "/edge: expected a blade edge longer than 0 and at most " + std::to_string(max_edge) + " m";
        return m;
      }
    }
    m.kind = ClientMessage::Kind::sample;
  } else {
    m.error = "/type: expected \"hello\", \"sample\", \"next\" or \"stop\"";
  }
  return m;
}

std::string format_hello(const ViewHello& h) {
  return json{{"type", "hello"},           {"protocol", kViewProtocol},  {"name", kViewProtocolName},
              {"frame_rate", h.frame_rate}, {"contact", h.contact},       {"regions", h.regions},
              {"latency", h.latency},       {"state_every", h.state_every}, {"max_edge", h.max_edge},
              {"probe_stiffness", h.probe_stiffness}, {"max_message", kViewMaxMessage}}
      .dump();
}

std::string format_mesh(const ViewTopology& t) {
  return json{{"type", "mesh"}, {"version", t.version}, {"nodes", t.nodes}, {"reference", t.reference},
              {"triangles", t.triangles}}
      .dump();
}

std::string format_state(const ViewState& s) {
  return json{{"type", "state"},
              {"frame", s.frame},
              {"t", s.time},
              {"tip", array3(s.tip)},
              {"force", array3(s.force)},
              {"contact", s.contact},
              {"blade", s.blade},
              {"compute_mean", s.compute_mean},
              {"compute_max", s.compute_max},
              {"start_lag_max", s.start_lag_max},
              {"window_frames", s.window_frames},
              {"deadline_misses", s.deadline_misses},
              {"events", s.events},
              {"cuts", s.cuts},
              {"samples", s.samples},
              {"samples_dropped", s.samples_dropped},
              {"topology", s.topology.version},
              {"nodes", s.topology.nodes},
              {"regions", !s.region.empty()}}
      .dump();
}

std::string format_error(const std::string& message) { return json{{"type", "error"}, {"message", message}}.dump(); }

void format_positions(const ViewState& s, std::string& out) {
  const std::size_t bytes = s.positions.size() * sizeof(float);
  out.resize(bytes + s.region.size());
  std::memcpy(out.data(), s.positions.data(), bytes);
  if (!s.region.empty()) std::memcpy(out.data() + bytes, s.region.data(), s.region.size());
}

}  // namespace softsim::haptic
