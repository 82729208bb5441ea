#include "softsim/fit/cross_validation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace softsim::fit {

int effective_folds(int samples, int requested) {
  if (requested <= 0 || requested > samples) return samples;
  return requested;
}

std::vector<int> assign_folds(int samples, int folds, std::uint64_t seed) {
  std::vector<int> order(samples);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  for (int i = samples - 1; i > 0; --i) {
    const int j = static_cast<int>(rng() % static_cast<std::uint64_t>(i + 1));
    std::swap(order[i], order[j]);
  }
  std::vector<int> fold(samples, 0);
  for (int i = 0; i < samples; ++i) fold[order[i]] = i % folds;
  return fold;
}

FoldDesigns::FoldDesigns(const Eigen::MatrixXd& design, int requested_folds, std::uint64_t seed,
                         const LmSettings& settings)
    : samples_(static_cast<int>(design.rows())), parameters_(static_cast<int>(design.cols())) {
  if (samples_ < 2) return;
  const int k = effective_folds(samples_, requested_folds);
  const std::vector<int> fold = assign_folds(samples_, k, seed);
  train_.resize(k);
  test_.resize(k);
  designs_.reserve(k);
  for (int f = 0; f < k; ++f) {
    for (int i = 0; i < samples_; ++i) (fold[i] == f ? test_[f] : train_[f]).push_back(i);
    designs_.emplace_back(design(train_[f], Eigen::all), settings);
  }
}

void FoldErrors::finish(CvScore& score) const {
  double total = 0.0;
  long n = 0;
  std::vector<double> fold_mse;
  for (std::size_t f = 0; f < sum_.size(); ++f) {
    total += sum_[f];
    n += count_[f];
    if (count_[f] > 0) fold_mse.push_back(sum_[f] / count_[f]);
  }
  score.predictions = n;
  score.mse = n > 0 ? total / n : 0.0;
  score.se = 0.0;
  if (fold_mse.size() > 1) {
    const double k = static_cast<double>(fold_mse.size());
    const double mean = std::accumulate(fold_mse.begin(), fold_mse.end(), 0.0) / k;
    double var = 0.0;
    for (double m : fold_mse) var += (m - mean) * (m - mean);
    var /= (k - 1.0);
    score.se = std::sqrt(var / k);
  }
}

void refuse(CvScore& score, FitStatus status, const std::string& message) {
  if (score.status != FitStatus::ok) return;
  score.status = status;
  score.message = message;
}

const char* to_string(Selection selection) {
  return selection == Selection::min_error ? "min" : "one_se";
}

int select_candidate(const std::vector<CvScore>& scores, const std::vector<int>& complexity,
                     Selection rule, double noise_floor_mse) {
  int best = -1;
  for (int i = 0; i < static_cast<int>(scores.size()); ++i) {
    if (!scores[i].ok()) continue;
    if (best < 0 || scores[i].mse < scores[best].mse) best = i;
  }
  if (best < 0) return -1;
  double threshold = std::max(scores[best].mse, noise_floor_mse);
  if (rule == Selection::one_standard_error) threshold += scores[best].se;
  int chosen = -1;
  for (int i = 0; i < static_cast<int>(scores.size()); ++i) {
    if (!scores[i].ok() || scores[i].mse > threshold) continue;
    if (chosen < 0 || complexity[i] < complexity[chosen] ||
        (complexity[i] == complexity[chosen] && scores[i].mse < scores[chosen].mse))
      chosen = i;
  }
  return chosen;
}

}  // namespace softsim::fit
