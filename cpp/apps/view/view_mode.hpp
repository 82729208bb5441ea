#pragma once
// haptic_sim view: the scene of a haptic_sim config, live, with its page served on one port
// (cpp/apps/haptic_sim.md, "The live scene in a browser").
#include "common/app.hpp"
#include "softsim/haptic/device_safety.hpp"
#include "softsim/haptic/haptic_config.hpp"
#include "softsim/haptic/haptic_run.hpp"
#include "view_args.hpp"

namespace softsim::view {

// Serves until stopped; returns the record of every frame (and writes the tip trajectory when
// asked). InputError for a web root without the page or a port that cannot be bound.
haptic::HapticRecord run_view(app::AppContext& ctx, const ViewArgs& args, const haptic::HapticConfig& config,
                              haptic::HapticScene& scene, haptic::ForceLimiter& limiter);

}  // namespace softsim::view
