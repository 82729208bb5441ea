#pragma once
// The visual state of the real-time loop: the deformed surface, at a lower rate than the force
// (a picture at 30-60 Hz against the device's 1 kHz), written after the frame's force has been
// answered so that it never delays the device. A compact binary stream a renderer reads (a file,
// or a named pipe made with mkfifo):
//   header   one ASCII line "softsim_surface 1 nodes N\n", then N int32 node indices (the
//            mesh's boundary nodes, ascending; little-endian as the machine writes them)
//   frames   per picture: float64 t (s, the device's time), then N × 3 float32 positions
//            x = X + u (m) of those nodes, in the same order
// The path obeys the output rules of every file a tool writes (io/output_guard.hpp), checked by
// the tool before anything is computed, with one exception: a named pipe is allowed. A regular
// file is recorded as written, so a failed run removes its partial stream. A stream that cannot
// be written any more (its pipe's reader left, the disk is full) stops: the live loop goes on,
// and the artifact says at which frame and why.
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::haptic {

struct VisualConfig {
  std::string path;  // empty: no visual stream
  int every = 33;    // frames per picture (33: about 30 Hz at 1 kHz)
};

class VisualStream {
 public:
  // InputError naming the path when it cannot be opened.
  VisualStream(const mesh::TetMesh& mesh, const VisualConfig& config);
  ~VisualStream();
  VisualStream(const VisualStream&) = delete;
  VisualStream& operator=(const VisualStream&) = delete;
  // After frame `frame` (1-based) at time `t` with displacement `u` (3 per node): a picture every
  // `every` frames.
  void after_frame(long frame, double t, const double* u);
  long pictures() const { return pictures_; }
  // The artifact's "visual" member: path, pictures written, and why and when the stream stopped.
  nlohmann::json payload() const;

 private:
  const mesh::TetMesh* mesh_;
  int every_;
  std::FILE* file_ = nullptr;
  std::string path_;
  std::vector<int> nodes_;
  std::vector<float> positions_;  // sized once
  long pictures_ = 0;
  long stopped_at_ = 0;     // frame at which writing failed (0: never)
  std::string stopped_why_;
};

}  // namespace softsim::haptic
