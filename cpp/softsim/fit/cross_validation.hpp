#pragma once
// k-fold cross-validation (002 §2.4: "m ... obtained by cross-validation [39]").
//
// Samples are dealt into k folds by a seeded shuffle (a portable Fisher–Yates on mt19937_64,
// so a seed gives the same folds on every platform). Each candidate model is fitted k times,
// each time without one fold, and scored by the mean squared error of its predictions on the
// held-out samples. The chosen candidate is the simplest one whose score is within one standard
// error of the best (Hastie, Tibshirani & Friedman, §7.10), or the best itself on request.
#include <cstdint>
#include <string>
#include <vector>

#include "softsim/fit/lm_fit.hpp"

namespace softsim::fit {

// Number of folds actually used: `requested` clamped to the sample count; 0 means leave-one-out.
int effective_folds(int samples, int requested);

// Fold index (0..folds-1) of every sample; fold sizes differ by at most one.
std::vector<int> assign_folds(int samples, int folds, std::uint64_t seed);

// The samples (rows of a design) dealt into folds, with each fold's training rows checked once
// (LinearDesign): everything of a cross-validation that does not depend on the data fitted, so
// that one split serves every right-hand side sampled at the same rows. Fewer than 2 samples
// give no folds.
class FoldDesigns {
 public:
  FoldDesigns(const Eigen::MatrixXd& design, int requested_folds, std::uint64_t seed, const LmSettings& settings);

  int samples() const { return samples_; }
  int parameters() const { return parameters_; }
  int folds() const { return static_cast<int>(designs_.size()); }
  const std::vector<int>& train(int fold) const { return train_[fold]; }
  const std::vector<int>& test(int fold) const { return test_[fold]; }
  const LinearDesign& design(int fold) const { return designs_[fold]; }

 private:
  int samples_;
  int parameters_;
  std::vector<std::vector<int>> train_;
  std::vector<std::vector<int>> test_;
  std::vector<LinearDesign> designs_;
};

struct CvScore {
  FitStatus status = FitStatus::ok;  // the first refusal met in any fold
  std::string message;
  int parameters = 0;
  double mse = 0.0;            // pooled over every held-out prediction
  double se = 0.0;             // standard error of the per-fold MSE
  double max_condition = 0.0;  // worst cond(AᵀA) met over the folds
  long predictions = 0;

  bool ok() const { return status == FitStatus::ok; }
};

// Collects held-out squared errors fold by fold.
class FoldErrors {
 public:
  explicit FoldErrors(int folds) : sum_(folds, 0.0), count_(folds, 0) {}
  void add(int fold, double squared_error) {
    sum_[fold] += squared_error;
    ++count_[fold];
  }
  // Fills mse, se and predictions.
  void finish(CvScore& score) const;

 private:
  std::vector<double> sum_;
  std::vector<long> count_;
};

// Marks the score as refused by a fold's fit, keeping the first reason.
void refuse(CvScore& score, FitStatus status, const std::string& message);

enum class Selection { min_error, one_standard_error };

const char* to_string(Selection selection);

// Index of the chosen candidate, or -1 when every candidate was refused. `complexity` orders
// the candidates from simplest (usually the parameter count). Scores below `noise_floor_mse`
// count as equal: data that a model reproduces to round-off do not favour a larger model.
int select_candidate(const std::vector<CvScore>& scores, const std::vector<int>& complexity,
                     Selection rule, double noise_floor_mse);

}  // namespace softsim::fit
