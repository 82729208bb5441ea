#pragma once
// haptic_sim view's transport: one port serving the page (HTTP, static files from the web root)
// and the live scene (a WebSocket speaking softsim-view, haptic/view_protocol.hpp), built on
// Boost.Beast. One client drives the scene at a time; a second one gets an error and is closed.
// A bad message gets an error on its connection only; nothing a client sends stops the frames.
#include <functional>
#include <string>

#include "softsim/haptic/view_loop.hpp"
#include "softsim/haptic/view_protocol.hpp"

namespace softsim::view {

struct ViewServerOptions {
  std::string host = "127.0.0.1";  // loopback only unless asked otherwise
  int port = 0;                    // 0: a free port
  std::string web_root;            // index.html, view.js and node_modules/three
  double state_rate = 60;          // states per second sent to the client (at most)
};

// Serves until a client sends "stop", SIGINT or SIGTERM arrives, or the loop ends by itself.
// `on_listen` receives the bound port. InputError when the address cannot be bound.
void serve_view(haptic::ViewLoop& loop, const haptic::ViewHello& hello, const ViewServerOptions& options,
                const std::function<void(int port)>& on_listen);

}  // namespace softsim::view
