#include "softsim/haptic/visual_stream.hpp"

#include <cerrno>
#include <cstdint>
#include <cstring>

#include <sys/stat.h>

#include "softsim/io/errors.hpp"
#include "softsim/io/output_guard.hpp"
#include "softsim/mesh/surface.hpp"

namespace softsim::haptic {

VisualStream::VisualStream(const mesh::TetMesh& mesh, const VisualConfig& config)
    : mesh_(&mesh), every_(config.every), path_(config.path), nodes_(mesh::boundary_nodes(mesh)) {
  if (every_ < 1) throw InputError("realtime.visual: every must be at least 1 frame");
  // A regular file is this run's output: an earlier file there is kept aside (a failed run puts
  // it back) and the stream starts a new file; a named pipe is opened as it is.
  struct stat st {};
  const bool pipe = ::stat(path_.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
  if (!pipe) {
    io::keep_previous(path_);
    std::remove(path_.c_str());
  }
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) throw InputError(path_ + ": cannot open the visual stream: " + std::strerror(errno));
  if (!pipe) io::record_written(path_);
  positions_.resize(3 * nodes_.size());
  const std::string header = "softsim_surface 1 nodes " + std::to_string(nodes_.size()) + "\n";
  std::vector<std::int32_t> index(nodes_.begin(), nodes_.end());
  if (std::fwrite(header.data(), 1, header.size(), file_) != header.size() ||
      std::fwrite(index.data(), sizeof(std::int32_t), index.size(), file_) != index.size() || std::fflush(file_) != 0)
    throw InputError(path_ + ": cannot write the visual stream: " + std::strerror(errno));
}

VisualStream::~VisualStream() {
  if (file_) std::fclose(file_);
}

void VisualStream::after_frame(long frame, double t, const double* u) {
  if (!file_ || frame % every_ != 0) return;
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    for (int c = 0; c < 3; ++c)
      positions_[3 * k + c] = static_cast<float>(mesh_->nodes[nodes_[k]][c] + u[3 * nodes_[k] + c]);
  if (std::fwrite(&t, sizeof t, 1, file_) != 1 ||
      std::fwrite(positions_.data(), sizeof(float), positions_.size(), file_) != positions_.size() ||
      std::fflush(file_) != 0) {
    // The reader of a pipe left (EPIPE) or the disk is full: the picture is lost, not the run.
    stopped_why_ = errno == EPIPE ? "the reader left" : std::strerror(errno);
    stopped_at_ = frame;
    std::fclose(file_);
    file_ = nullptr;
    return;
  }
  ++pictures_;
}

nlohmann::json VisualStream::payload() const {
  return {{"path", path_},
          {"every", every_},
          {"pictures", pictures_},
          {"stopped_at_frame", stopped_at_ ? nlohmann::json(stopped_at_) : nlohmann::json(nullptr)},
          {"stopped_because", stopped_at_ ? nlohmann::json(stopped_why_) : nlohmann::json(nullptr)}};
}

}  // namespace softsim::haptic
