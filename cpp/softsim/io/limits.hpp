#pragma once
// The limits every reader and every run applies before it trusts its input: how deep a JSON
// document may nest, how large an input file may be, and how much memory a run may plan to use.
// Each is refused with an InputError (exit 2) naming the file or the config member, never met
// as a crash, a std::bad_alloc or an endless read. The two sizes can be raised for a large
// machine through the environment:
//   SOFTSIM_MAX_INPUT_MB    largest input file read (default 4096 MiB)
//   SOFTSIM_MEMORY_LIMIT_MB largest memory estimate of a run (default 80 % of physical memory)
//   SOFTSIM_MAX_ELEMENT_UPDATES  most element updates a simulation may ask for (default 1e11:
//                           about half an hour of one core on the TLED kernel), so that a step
//                           count of 2^31 is refused rather than run for hours
//   SOFTSIM_GMSH_TIMEOUT_S  wall-clock seconds Gmsh may take to fill a surface with tetrahedra
//                           (default 600; meshing/bounded_child.hpp)
#include <cstddef>
#include <cstdint>
#include <string>

namespace softsim::io {

class JsonReader;

// Deepest nesting of arrays and objects accepted in any JSON document (configs, artifacts). Ours
// nest at most 6 deep; the bound keeps every recursive walk of a parsed document (copying,
// flattening, destroying) far from the stack's end.
constexpr std::size_t kMaxJsonDepth = 64;

std::uint64_t max_input_bytes();
std::uint64_t memory_limit_bytes();
double max_element_updates();
double gmsh_timeout_seconds();

// Refuses a run whose work (element updates: steps x elements) exceeds max_element_updates(),
// naming the member `key` of `at` that sets it.
void require_work(const JsonReader& at, const std::string& key, double element_updates);

// "1.5 GiB": a byte count for messages.
std::string format_bytes(double bytes);

// Refuses a run whose memory estimate (bytes, computed from the config before anything is
// allocated) exceeds memory_limit_bytes(), naming the member `key` of `at` that sets the size,
// the estimate and the limit. `what` says what would take the memory ("the node arrays").
void require_memory(const JsonReader& at, const std::string& key, double bytes, const std::string& what);
// The same where the estimate needs more than the config (a size read from an input file): a
// ConfigInputError at the config member `pointer` (run_app names the config file).
void require_memory(const std::string& pointer, double bytes, const std::string& what);

}  // namespace softsim::io
