// libFuzzer target: the bytes as a .vtu file that mesher imports, through run_app (fuzz_app.hpp):
// the reader mesher picks by the extension, the checks of the mesh built, the artifact at --out.
#include <cstddef>
#include <cstdint>

#include "fuzz_app.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::run_mesher_on_file(data, size, ".vtu");
  return 0;
}
