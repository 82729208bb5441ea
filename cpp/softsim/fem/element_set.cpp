#include "softsim/fem/element_set.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "softsim/fem/element_kernels.hpp"
#include "softsim/fem/element_response.hpp"
#include "softsim/fem/law_kernels.hpp"
#include "softsim/fem/nodal_pressure.hpp"

namespace softsim::fem {

namespace {

int round_up(int n, int b) { return (n + b - 1) / b * b; }

// Runs `work`, adding its duration to seconds[kind] when timing is requested.
template <class Work>
void timed(double* seconds, ElementKind kind, Work&& work) {
  if (!seconds) return work();
  const auto t0 = std::chrono::steady_clock::now();
  work();
  seconds[static_cast<int>(kind)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// Approximate relative costs, measured once with bench_dhd (BM_Kernel per element and kind,
// one thread, the paper's 14450-tet cuboid, on the development machine) and rounded. They are
// hints for balancing threads only: a different machine gives other ratios and merely a less
// even split. They cannot change results, since each element's forces are computed the same
// way in whatever range it falls and every node gathers its corner forces in a fixed order.
double ElementSet::relative_cost(ElementKind kind) {
  switch (kind) {
    case ElementKind::linear: return 0.9;  // element by element (the assembled rows: kLinearBlockCost)
    case ElementKind::tled: return 1.0;
    case ElementKind::corotational: return 4.8;
    case ElementKind::anp: return 1.8;  // with its nodal-pressure pre-pass
    case ElementKind::smoothed: return 9.0;  // scalar path with its edge pre-pass (results/validation/incompressible_cost.md)
  }
  return 1.0;
}

ElementSet::ElementSet(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds,
                       const Material& material, int tile_nodes, LinearForces linear_forces)
    : num_nodes_(mesh.num_nodes()),
      material_(material),
      inversion_robust_(material::inversion_robust(material.law)),
      kinds_(kinds) {
  if (static_cast<int>(kinds.size()) != mesh.num_tets())
    throw std::invalid_argument("ElementSet: one kind per element is required");
  // An element's tile key: its highest node index. Inside a group elements are sorted by it, so
  // that a sweep over the nodes meets the elements in order (see build_tiles).
  std::vector<int> key(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e)
    key[e] = *std::max_element(mesh.tets[e].begin(), mesh.tets[e].end());
  // Groups in a fixed kind order, each padded to a block multiple.
  int slot = 0;
  for (int kk = 0; kk < kNumElementKinds; ++kk) {
    const ElementKind kind = static_cast<ElementKind>(kk);
    Group g;
    g.kind = kind;
    g.begin = slot;
    for (int e = 0; e < mesh.num_tets(); ++e)
      if (kinds[e] == kind) {
        original_.push_back(e);
        ++g.count;
      }
    if (g.count == 0) continue;  // a kind the scene does not have costs nothing
    std::stable_sort(original_.begin() + g.begin, original_.end(), [&](int a, int b) { return key[a] < key[b]; });
    slot = round_up(g.begin + g.count, kBlock);
    original_.resize(slot, -1);
    g.end = slot;
    groups_.push_back(g);
  }
  stride_ = slot;
  if (linear_forces == LinearForces::assembled && count(ElementKind::linear) > 0) {
    linear_rows_ = LinearStiffnessRows(mesh, kinds, material);
    linear_force_.assign(3 * static_cast<std::size_t>(num_nodes_), 0.0);
  }
  // Slots whose corner forces go through the buffer (assembled linear elements do not).
  const auto through_buffer = [&](int e) { return e >= 0 && (kinds[e] != ElementKind::linear || !assembled_linear()); };
  for (auto& v : node_offset_) v.assign(stride_, 0);
  for (auto& v : grad_) v.assign(stride_, 0.0);
  volume_.assign(stride_, 0.0);
  buffer_.assign(static_cast<std::size_t>(12) * stride_, 0.0);
  scratch_.assign(stride_, 0.0);

  std::vector<int> degree(num_nodes_ + 1, 0);
  for (int i = 0; i < stride_; ++i) {
    const int e = original_[i];
    if (e < 0) continue;
    const auto& t = mesh.tets[e];
    const TetShape sh = tet_shape(mesh, e);
    if (!(sh.volume > 0))
      throw std::invalid_argument("ElementSet: element " + std::to_string(e) + " has no positive volume");
    for (int a = 0; a < 4; ++a) {
      node_offset_[a][i] = 3 * t[a];
      if (through_buffer(e)) ++degree[t[a]];
    }
    for (int a = 1; a < 4; ++a)
      for (int c = 0; c < 3; ++c) grad_[3 * (a - 1) + c][i] = sh.grad[a][c];
    volume_[i] = sh.volume;
  }
  incidence_begin_.assign(num_nodes_ + 1, 0);
  for (int n = 0; n < num_nodes_; ++n) incidence_begin_[n + 1] = incidence_begin_[n] + degree[n];
  incidence_end_.assign(incidence_begin_.begin() + 1, incidence_begin_.end());
  incidence_.resize(incidence_begin_[num_nodes_]);
  std::vector<int> fill(incidence_begin_.begin(), incidence_begin_.end() - 1);
  for (int i = 0; i < stride_; ++i) {
    const int e = original_[i];
    if (!through_buffer(e)) continue;
    for (int a = 0; a < 4; ++a) incidence_[fill[mesh.tets[e][a]]++] = 3 * a * stride_ + i;
  }
  build_tiles(key, std::max(tile_nodes, 1));
  build_nodal_pressure(mesh);
  if (material::fibre_of(material_.law)) {
    for (auto& v : fibre_) v.assign(stride_, 0.0);
    for (int i = 0; i < stride_; ++i)
      if (original_[i] >= 0) {
        const Eigen::Vector3d a = material_.fibre(original_[i]);
        for (int c = 0; c < 3; ++c) fibre_[c][i] = a[c];
      }
  }
  state_size_ = material::state_size(material_.law);
  if (state_size_ > 0 && count(ElementKind::smoothed) > 0)
    throw std::invalid_argument("ElementSet: smoothed elements take no law with internal variables");
  if (state_size_ > 0)
    for (auto& v : law_state_) v.assign(static_cast<std::size_t>(state_size_) * stride_, 0.0);
  slot_of_.assign(mesh.num_tets(), -1);
  for (int i = 0; i < stride_; ++i)
    if (original_[i] >= 0) slot_of_[original_[i]] = i;
  removed_.assign(mesh.num_tets(), 0);
}

std::vector<int> ElementSet::remove_elements(const mesh::TetMesh& mesh, const std::vector<int>& elements) {
  std::vector<int> done;
  std::vector<int> anp_nodes;
  for (int e : elements) {
    if (e < 0 || e >= static_cast<int>(removed_.size()))
      throw std::invalid_argument("ElementSet: element " + std::to_string(e) + " out of range");
    if (removed_[e]) continue;
    removed_[e] = 1;
    ++num_removed_;
    done.push_back(e);
    const int i = slot_of_[e];
    if (kinds_[e] == ElementKind::linear && assembled_linear()) linear_rows_.remove_element(mesh, e, material_);
    if (volumetric_at_nodes(kinds_[e]))
      for (int a : mesh.tets[e]) anp_nodes.push_back(a);
    for (auto& g : grad_) g[i] = 0.0;
    volume_[i] = 0.0;
    for (auto& buffer : law_state_)  // a removed slot holds no stress (the others keep theirs)
      for (int c = 0; c < state_size_; ++c) buffer[static_cast<std::size_t>(c) * stride_ + i] = 0.0;
    if (!volume_ratio_.empty()) volume_ratio_[i] = 1.0;
  }
  // ANP: V_a = Σ ⁰V_e / 4 over the corners' remaining ANP elements, w_ae = ⁰V_e / (4 V_a), in the
  // stored order (a removed element keeps its entry with weight 0).
  std::sort(anp_nodes.begin(), anp_nodes.end());
  anp_nodes.erase(std::unique(anp_nodes.begin(), anp_nodes.end()), anp_nodes.end());
  for (int a : anp_nodes) reweigh_nodal_volume(a);
  if (smoothing_ && !done.empty()) rebuild_smoothing(mesh);
  return done;
}

// The smoothing edges of the smoothed elements still in `mesh` (not removed), from scratch: a
// cut changes the domains of the edges around it (and a split the edges' nodes).
void ElementSet::rebuild_smoothing(const mesh::TetMesh& mesh) {
  std::vector<ElementKind> live = kinds_;
  std::vector<TetShape> shapes(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (removed_[e]) live[e] = ElementKind::linear;  // any kind but smoothed: no edge domain
    shapes[e] = shape(slot_of_[e]);
  }
  smoothing_.emplace(mesh, live, shapes);
  edge_stress_.assign(smoothing_->num_edges(), Eigen::Matrix3d::Zero());
}

// V_a = Σ ⁰V_e / 4 over the ANP elements still at node a (a removed one has ⁰V = 0; one a split
// moved away no longer has a as a corner) and w_ae = ⁰V_e / (4 V_a), in the stored order.
void ElementSet::reweigh_nodal_volume(int a) {
  const auto share = [&](int slot) {
    for (const auto& offset : node_offset_)
      if (offset[slot] == 3 * a) return 0.25 * volume_[slot];
    return 0.0;
  };
  double v = 0;
  for (int p = anp_.begin[a]; p < anp_.begin[a + 1]; ++p) v += share(anp_.element[p]);
  anp_.volume[a] = v;
  for (int p = anp_.begin[a]; p < anp_.begin[a + 1]; ++p) anp_.weight[p] = v > 0 ? share(anp_.element[p]) / v : 0.0;
}

void ElementSet::split_nodes(const mesh::TetMesh& mesh, const std::vector<NodeCopy>& copies) {
  for (std::size_t k = 0; k < copies.size(); ++k) {
    const NodeCopy& c = copies[k];
    if (c.copy != num_nodes_ + static_cast<int>(k) || c.copy >= mesh.num_nodes())
      throw std::invalid_argument("ElementSet::split_nodes: copies must be numbered after the nodes, in order");
    for (int e : c.elements)
      if (kinds_[e] == ElementKind::linear && assembled_linear())
        throw std::invalid_argument("ElementSet::split_nodes: element " + std::to_string(e) +
                                    " is an assembled linear element (build the set with per-element linear forces)");
  }
  for (const NodeCopy& c : copies) {
    ++num_nodes_;
    const auto moved = [&](int slot) { return std::binary_search(c.elements.begin(), c.elements.end(), original_[slot]); };
    for (int e : c.elements) {
      const int i = slot_of_[e];
      for (auto& offset : node_offset_)
        if (offset[i] == 3 * c.node) offset[i] = 3 * c.copy;
    }
    // The node keeps the corners that stay, in their order; the copy's follow at the end.
    const int copy_begin = static_cast<int>(incidence_.size());
    int keep = incidence_begin_[c.node];
    for (int p = incidence_begin_[c.node]; p < incidence_end_[c.node]; ++p) {
      const int o = incidence_[p];
      if (moved(o % stride_)) incidence_.push_back(o);
      else incidence_[keep++] = o;
    }
    incidence_end_[c.node] = keep;
    incidence_begin_.resize(c.copy);  // drops the set-up's end sentinel: ranges are [begin, end) now
    incidence_begin_.push_back(copy_begin);
    incidence_end_.push_back(static_cast<int>(incidence_.size()));
    first_tile_.push_back(num_tiles_ - 1);
    if (assembled_linear()) linear_force_.resize(3 * static_cast<std::size_t>(num_nodes_), 0.0);
    if (has_nodal_pressure()) {
      // The copy's entries follow at the end; the node keeps the moved ones at weight 0.
      anp_.begin.push_back(anp_.begin.back());
      for (int p = anp_.begin[c.node]; p < anp_.begin[c.node + 1]; ++p)
        if (moved(anp_.element[p])) {
          anp_.element.push_back(anp_.element[p]);
          anp_.weight.push_back(0.0);
          ++anp_.begin.back();
        }
      anp_.volume.push_back(0.0);
      reweigh_nodal_volume(c.node);
      reweigh_nodal_volume(c.copy);
      nodal_pressure_.resize(3 * static_cast<std::size_t>(num_nodes_), 0.0);
    }
  }
  if (smoothing_ && !copies.empty()) rebuild_smoothing(mesh);
}

void ElementSet::build_nodal_pressure(const mesh::TetMesh& mesh) {
  if (!has_nodal_pressure()) return;
  std::vector<int> slot(mesh.num_tets(), -1);
  std::vector<double> volume(mesh.num_tets(), 0.0);
  for (int i = 0; i < stride_; ++i)
    if (original_[i] >= 0) {
      slot[original_[i]] = i;
      volume[original_[i]] = volume_[i];
    }
  anp_ = nodal_volumes(mesh, kinds_, volume);
  for (int& e : anp_.element) e = slot[e];
  volume_ratio_.assign(stride_, 1.0);
  nodal_pressure_.assign(3 * static_cast<std::size_t>(num_nodes_), 0.0);
  if (count(ElementKind::smoothed) > 0) {
    std::vector<TetShape> shapes(mesh.num_tets());
    for (int e = 0; e < mesh.num_tets(); ++e) shapes[e] = shape(slot[e]);
    smoothing_.emplace(mesh, kinds_, shapes);
    smoothed_gradient_.assign(mesh.num_tets(), Eigen::Matrix3d::Identity());
    edge_stress_.assign(smoothing_->num_edges(), Eigen::Matrix3d::Zero());
  }
}

// F = I + Σ_{a=1..3} (u_a − u_0) ⊗ ∇N_a of slot i, straight from the stored gradients (∇N_0 is
// minus the sum of the others).
Eigen::Matrix3d ElementSet::slot_gradient(int i, const double* u) const {
  const double* u0 = u + node_offset_[0][i];
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int a = 1; a < 4; ++a) {
    const double* ua = u + node_offset_[a][i];
    for (int r = 0; r < 3; ++r) {
      const double d = ua[r] - u0[r];
      for (int c = 0; c < 3; ++c) F(r, c) += d * grad_[3 * (a - 1) + c][i];
    }
  }
  return F;
}

// Corner forces ⁰V (P̄_iso + p̄ cof F) ∇N_a of the smoothed slots [begin, end): P̄_iso the mean
// of the element's six edge stresses, p̄ the mean of its corners' nodal pressures.
void ElementSet::compute_smoothed(const double* u, int begin, int end) {
  (void)u;  // F was stored by the pre-pass
  double* __restrict buffer = buffer_.data();
  for (int i = begin; i < end; ++i) {
    const int e = original_[i];
    Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
    if (e >= 0 && !removed_[e]) {
      double pbar = 0;
      for (int a = 0; a < 4; ++a) pbar += 0.25 * nodal_pressure_[node_offset_[a][i]];
      P = volume_[i] * (smoothing_->element_stress(e, edge_stress_.data()) + pbar * cofactor(smoothed_gradient_[e]));
    }
    double f0[3] = {0, 0, 0};
    for (int a = 1; a < 4; ++a)
      for (int r = 0; r < 3; ++r) {
        const double f = P(r, 0) * grad_[3 * (a - 1)][i] + P(r, 1) * grad_[3 * (a - 1) + 1][i] +
                         P(r, 2) * grad_[3 * (a - 1) + 2][i];
        buffer[static_cast<std::size_t>(3 * a + r) * stride_ + i] = f;
        f0[r] -= f;
      }
    for (int r = 0; r < 3; ++r) buffer[static_cast<std::size_t>(r) * stride_ + i] = f0[r];
  }
}

void ElementSet::compute_volume_ratios(const double* u, int tile, KernelStats& stats) {
  const int G = static_cast<int>(groups_.size());
  for (int gi = 0; gi < G; ++gi) {
    if (groups_[gi].kind != ElementKind::anp) continue;
    const auto [b, e] = tile_blocks_[static_cast<std::size_t>(tile) * G + gi];
    // An inversion-robust law's ANP elements may invert: their J is no failure (min_j untouched).
    double unchecked = 1e300;
    double& min_j = inversion_allowed(ElementKind::anp) ? unchecked : stats.min_j;
    if (b < e) kernels::volume_ratio_kernel(view(), u, b, e, volume_ratio_.data(), min_j);
  }
  for (int gi = 0; gi < G; ++gi) {
    if (groups_[gi].kind != ElementKind::smoothed) continue;
    const auto [b, e] = tile_blocks_[static_cast<std::size_t>(tile) * G + gi];
    for (int i = b; i < e; ++i) {
      if (original_[i] < 0) continue;
      const Eigen::Matrix3d F = slot_gradient(i, u);
      smoothed_gradient_[original_[i]] = F;
      volume_ratio_[i] = F.determinant();
      stats.min_j = std::min(stats.min_j, volume_ratio_[i]);
    }
  }
}

void ElementSet::update_nodal_pressures(int begin, int end) {
  const double kappa = material_.volumetric_modulus;
  for (int a = begin; a < end; ++a)
    if (anp_.has_elements(a))
      nodal_pressure_[3 * static_cast<std::size_t>(a)] = kappa * (nodal_volume_ratio(anp_, a, volume_ratio_.data()) - 1.0);
  if (smoothing_)
    smoothing_->edge_stresses(material_, smoothed_gradient_.data(), smoothing_->node_edge_begin(begin),
                              smoothing_->node_edge_begin(end), edge_stress_.data());
}

double ElementSet::nodal_volumetric_energy(const double* volume_ratio) const {
  if (!has_nodal_pressure()) return 0.0;
  const double kappa = material_.volumetric_modulus;
  double w = 0;
  for (int a = 0; a < num_nodes_; ++a) {
    if (!anp_.has_elements(a)) continue;
    const double Ja = nodal_volume_ratio(anp_, a, volume_ratio);
    w += anp_.volume[a] * 0.5 * kappa * (Ja - 1.0) * (Ja - 1.0);
  }
  return w;
}

void ElementSet::build_tiles(const std::vector<int>& key, int tile_nodes) {
  num_tiles_ = std::max(1, (num_nodes_ + tile_nodes - 1) / tile_nodes);
  const int G = static_cast<int>(groups_.size());
  tile_blocks_.assign(static_cast<std::size_t>(num_tiles_) * G, {0, 0});
  std::vector<int> slot_tile(stride_, 0);
  for (int gi = 0; gi < G; ++gi) {
    const Group& g = groups_[gi];
    int tile = 0;
    tile_blocks_[gi] = {g.begin, g.begin};
    for (int b = g.begin; b < g.end; b += kBlock) {
      int block_key = 0;
      for (int i = b; i < b + kBlock; ++i)
        if (original_[i] >= 0) block_key = std::max(block_key, key[original_[i]]);
      // Keys are sorted inside the group, so the tiles of consecutive blocks never decrease.
      const int t = std::max(tile, std::min(block_key / tile_nodes, num_tiles_ - 1));
      for (; tile < t; ++tile) {
        const int end = tile_blocks_[static_cast<std::size_t>(tile) * G + gi].second;
        tile_blocks_[static_cast<std::size_t>(tile + 1) * G + gi] = {end, end};
      }
      tile_blocks_[static_cast<std::size_t>(tile) * G + gi].second = b + kBlock;
      for (int i = b; i < b + kBlock; ++i) slot_tile[i] = tile;
    }
    for (; tile + 1 < num_tiles_; ++tile) {
      const int end = tile_blocks_[static_cast<std::size_t>(tile) * G + gi].second;
      tile_blocks_[static_cast<std::size_t>(tile + 1) * G + gi] = {end, end};
    }
  }
  // A node is ready once the last tile holding one of its elements is done. A node without
  // elements through the buffer (none, or only assembled linear ones) is ready in the tile of
  // its index, which spreads the linear rows over the sweep.
  std::vector<int> ready_tile(num_nodes_, 0);
  first_tile_.assign(num_nodes_, 0);
  for (int n = 0; n < num_nodes_; ++n) {
    int lo = num_tiles_, hi = 0;
    for (int p = incidence_begin_[n]; p < incidence_end_[n]; ++p) {
      const int t = slot_tile[incidence_[p] % stride_];
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    if (lo > hi) lo = hi = std::min(n / tile_nodes, num_tiles_ - 1);
    first_tile_[n] = lo;
    ready_tile[n] = hi;
  }
  ready_begin_.assign(num_tiles_ + 1, 0);
  for (int n = 0; n < num_nodes_; ++n) ++ready_begin_[ready_tile[n] + 1];
  for (int t = 0; t < num_tiles_; ++t) ready_begin_[t + 1] += ready_begin_[t];
  ready_nodes_.resize(num_nodes_);
  std::vector<int> fill(ready_begin_.begin(), ready_begin_.end() - 1);
  for (int n = 0; n < num_nodes_; ++n) ready_nodes_[fill[ready_tile[n]]++] = n;
}

void ElementSet::reset_law_state() {
  for (auto& buffer : law_state_) std::fill(buffer.begin(), buffer.end(), 0.0);
}

kernels::LawData ElementSet::law_data(const StepClock& clock) {
  kernels::LawData d;
  if (!fibre_[0].empty())
    for (int c = 0; c < 3; ++c) d.fibre[c] = fibre_[c].data();
  if (state_size_ > 0) {
    d.state_in = law_state_[clock.step & 1].data();
    d.state_out = law_state_[(clock.step + 1) & 1].data();
  }
  d.stride = stride_;
  d.dt = clock.dt;
  return d;
}

void ElementSet::compute_tile(const double* u, int tile, KernelStats& stats, double* seconds, const StepClock& clock) {
  const int G = static_cast<int>(groups_.size());
  for (int gi = 0; gi < G; ++gi) {
    // Named copies, not a structured binding: the lambda below captures them (C++17 forbids
    // capturing bindings).
    const int b = tile_blocks_[static_cast<std::size_t>(tile) * G + gi].first;
    const int e = tile_blocks_[static_cast<std::size_t>(tile) * G + gi].second;
    if (b >= e || !computed_per_element(groups_[gi])) continue;
    timed(seconds, groups_[gi].kind, [&] { compute_group(groups_[gi], u, b, e, stats, clock); });
  }
  if (assembled_linear())
    timed(seconds, ElementKind::linear,
          [&] { compute_linear_rows(u, ready_nodes_begin(tile), ready_nodes_end(tile)); });
}

void ElementSet::compute_linear_rows(const double* u, const int* node_begin, const int* node_end) {
  linear_rows_.multiply_rows(node_begin, node_end, u, linear_force_.data());
}

double ElementSet::tile_cost(int tile) const {
  const int G = static_cast<int>(groups_.size());
  double c = kNodeCost * (ready_begin_[tile + 1] - ready_begin_[tile]);
  for (int gi = 0; gi < G; ++gi) {
    const auto [b, e] = tile_blocks_[static_cast<std::size_t>(tile) * G + gi];
    if (computed_per_element(groups_[gi])) c += relative_cost(groups_[gi].kind) * (e - b);
  }
  if (assembled_linear())
    for (const int* n = ready_nodes_begin(tile); n != ready_nodes_end(tile); ++n)
      c += kLinearBlockCost * linear_rows_.row_blocks(*n);
  return c;
}

int ElementSet::count(ElementKind kind) const {
  for (const auto& g : groups_)
    if (g.kind == kind) return g.count;
  return 0;
}

kernels::SoaView ElementSet::view() {
  return kernels::SoaView{
      node_offset_[0].data(), node_offset_[1].data(), node_offset_[2].data(), node_offset_[3].data(),
      {grad_[0].data(), grad_[1].data(), grad_[2].data(), grad_[3].data(), grad_[4].data(), grad_[5].data(),
       grad_[6].data(), grad_[7].data(), grad_[8].data()},
      volume_.data(), buffer_.data(), stride_};
}

void ElementSet::compute_group(const Group& g, const double* u, int begin, int end, KernelStats& stats,
                               const StepClock& clock) {
  const kernels::SoaView s = view();
  const double mu = material_.lame.mu, lambda = material_.lame.lambda;
  switch (g.kind) {
    case ElementKind::linear: kernels::linear_kernel(s, u, begin, end, mu, lambda); break;
    case ElementKind::tled:
      kernels::tled_forces(material_.law, s, u, begin, end, scratch_.data(), stats.min_j, law_data(clock));
      break;
    case ElementKind::corotational:
      kernels::corotational_kernel(s, u, begin, end, mu, lambda, scratch_.data(), stats.min_j);
      break;
    case ElementKind::anp:
      kernels::anp_forces(material_.isochoric, s, u, begin, end, nodal_pressure_.data(), scratch_.data(), stats.min_j,
                          law_data(clock));
      break;
    case ElementKind::smoothed: compute_smoothed(u, begin, end); break;
  }
}

void ElementSet::compute(const double* u, KernelStats& stats, const StepClock& clock) {
  if (has_nodal_pressure()) {
    for (int t = 0; t < num_tiles_; ++t) compute_volume_ratios(u, t, stats);
    update_nodal_pressures(0, num_nodes_);
  }
  if (assembled_linear())  // every node is ready in exactly one tile
    for (int t = 0; t < num_tiles_; ++t) compute_linear_rows(u, ready_nodes_begin(t), ready_nodes_end(t));
  for (const Group& g : groups_)
    if (computed_per_element(g)) compute_group(g, u, g.begin, g.end, stats, clock);
}

std::vector<int> ElementSet::balanced_ranges(int parts) const {
  parts = std::max(parts, 1);
  // Cost per block, then cut the cumulative cost at equal shares.
  const int blocks = stride_ / kBlock;
  std::vector<double> cum(blocks + 1, 0.0);
  for (int b = 0; b < blocks; ++b) {
    double c = 0;
    for (const Group& g : groups_)
      if (b * kBlock >= g.begin && b * kBlock < g.end) c = relative_cost(g.kind);
    cum[b + 1] = cum[b] + c;
  }
  std::vector<int> cuts(parts + 1, 0);
  int b = 0;
  for (int p = 1; p < parts; ++p) {
    const double target = cum[blocks] * p / parts;
    while (b < blocks && cum[b + 1] <= target) ++b;
    cuts[p] = b * kBlock;
  }
  cuts[parts] = stride_;
  return cuts;
}

TetShape ElementSet::shape(int i) const {
  TetShape sh;
  sh.volume = volume_[i];
  for (int a = 1; a < 4; ++a)
    sh.grad[a] = Eigen::Vector3d(grad_[3 * (a - 1)][i], grad_[3 * (a - 1) + 1][i], grad_[3 * (a - 1) + 2][i]);
  sh.grad[0] = -(sh.grad[1] + sh.grad[2] + sh.grad[3]);
  return sh;
}

Corners ElementSet::corners(int i, const double* u) const {
  Corners c;
  for (int a = 0; a < 4; ++a) {
    const int o = node_offset_[a][i];
    c[a] = Eigen::Vector3d(u[o], u[o + 1], u[o + 2]);
  }
  return c;
}

void ElementSet::energies(const double* u, int begin, int end, double* energy, double* volume_ratio,
                          double& min_j, int& min_j_element) const {
  for (int i = begin; i < end; ++i) {
    const int e = original_[i];
    if (e < 0) {
      energy[i] = 0.0;
      volume_ratio[i] = 1.0;
      continue;
    }
    const TetShape sh = shape(i);
    const Corners c = corners(i, u);
    const double J = fem::volume_ratio(sh, c);
    volume_ratio[i] = J;
    const bool may_invert = inversion_allowed(kinds_[e]);
    if (J < min_j && !may_invert) {
      min_j = J;
      min_j_element = e;
    }
    if (kinds_[e] == ElementKind::smoothed) {  // its share of its edges' isochoric energy
      energy[i] = removed_[e] ? 0.0 : smoothing_->element_energy(material_, e, u);
      continue;
    }
    energy[i] = J > 0 || may_invert || kinds_[e] == ElementKind::linear
                    ? with_element_material(material_, e, [&](const Material& m) { return element_energy(m, kinds_[e], sh, c); })
                    : 0.0;
  }
}

}  // namespace softsim::fem
