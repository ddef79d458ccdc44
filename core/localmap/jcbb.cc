#include "core/localmap/jcbb.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/common/normal_quantile.h"

namespace atlas {
namespace {

double WilsonHilferty(double z, int dof) {
  const double k = dof;
  const double h = 2.0 / (9.0 * k);
  const double t = 1.0 - h + z * std::sqrt(h);
  return k * t * t * t;
}

struct TieHypothesis {
  std::vector<int> pair_of;
  double d2 = 0.0;
};

class Search {
 public:
  static constexpr size_t kMaxTies = 8;
  Search(int num_observations, const std::vector<CandidatePair>& candidates,
         const JointCovariance& cov, const JcbbOptions& options)
      : cands_(candidates), cov_(cov), options_(options) {
    // Candidates grouped by observation (CSR), each group by increasing individual distance.
    start_.assign(num_observations + 1, 0);
    for (const CandidatePair& c : candidates) {
      if (c.observation >= 0 && c.observation < num_observations) ++start_[c.observation + 1];
    }
    for (int j = 0; j < num_observations; ++j) start_[j + 1] += start_[j];
    grouped_.resize(start_[num_observations]);
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
      const int j = candidates[c].observation;
      if (j >= 0 && j < num_observations) grouped_[fill[j]++] = c;
    }
    for (int j = 0; j < num_observations; ++j) {
      if (start_[j] == start_[j + 1]) continue;
      std::sort(grouped_.begin() + start_[j], grouped_.begin() + start_[j + 1],
                [&](int a, int b) { return candidates[a].d2 < candidates[b].d2; });
      order_.push_back(j);
    }
    std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
      return start_[a + 1] - start_[a] < start_[b + 1] - start_[b];
    });
    ties.reserve(kMaxTies);
    const int n = static_cast<int>(order_.size());
    const double z = NormalQuantile(options.joint_gate);
    gate_.resize(n + 1);
    gate_[0] = 0.0;
    for (int k = 1; k <= n; ++k) {
      gate_[k] = k == 1 ? -2.0 * std::log(1.0 - options.joint_gate) : WilsonHilferty(z, 2 * k);
    }
    const int dim = 2 * n;
    l_.assign(static_cast<size_t>(dim) * dim, 0.0);
    y_.assign(dim, 0.0);
    ycum_.assign(dim, 0.0);
    x_.assign(2 * static_cast<size_t>(dim), 0.0);
    stack_.assign(n, -1);
    version_.assign(n, 0);
    cache_.resize(static_cast<size_t>(n) * candidates.size());
    current_pair_of_.assign(num_observations, -1);
    int max_feature = 0;
    for (const CandidatePair& c : candidates) max_feature = std::max(max_feature, c.feature);
    feature_use_.assign(max_feature + 1, 0);
    dim_ = dim;
  }

  void Run() { Visit(0, 0, 0.0); }

  int nodes = 0;
  bool exhausted = false;
  int best_pairings = -1;
  double best_d2 = 0.0;
  std::vector<int> best_pair_of;
  std::vector<TieHypothesis> ties;  // hypotheses with best_pairings pairings, the best included

 private:
  double& L(int r, int c) { return l_[static_cast<size_t>(r) * dim_ + c]; }

  // v^T S^-1 v for the 2x2 S = (s00 s01; s01 s11); +inf if S is not positive definite.
  static double Increment(double s00, double s01, double s11, double v0, double v1) {
    const double det = s00 * s11 - s01 * s01;
    if (!(s00 > 0.0) || !(det > 0.0)) return std::numeric_limits<double>::infinity();
    return (s11 * v0 * v0 - 2.0 * s01 * v0 * v1 + s00 * v1 * v1) / det;
  }

  double BestTieD2() const {
    double best = 1e300;
    for (const TieHypothesis& t : ties) best = std::min(best, t.d2);
    return best;
  }

  void Record(double d2, int pairings) {
    if (pairings > best_pairings) {
      best_pairings = pairings;
      ties.clear();
    }
    constexpr size_t kMaxTies = 8;
    if (ties.size() == kMaxTies) {
      auto worst = std::max_element(ties.begin(), ties.end(),
                                    [](const auto& a, const auto& b) { return a.d2 < b.d2; });
      if (worst->d2 <= d2) return;
      *worst = TieHypothesis{current_pair_of_, d2};
    } else {
      ties.push_back(TieHypothesis{current_pair_of_, d2});
    }
  }

  // Level `level` of the search; `k` pairings so far with joint distance d2.
  void Visit(int level, int k, double d2) {
    const int n = static_cast<int>(order_.size());
    if (k + (n - level) < best_pairings) return;
    // D^2 only grows down a branch: one that cannot beat the best number of pairings and is
    // already beyond the ambiguity margin of the best hypothesis can neither win nor be a rival.
    if (k + (n - level) == best_pairings && d2 > BestTieD2() + options_.ambiguity_margin) return;
    if (nodes >= options_.node_budget) {
      exhausted = true;
      return;
    }
    ++nodes;
    if (level == n) {
      Record(d2, k);
      return;
    }
    const int j = order_[level];
    for (int g = start_[j]; g < start_[j + 1]; ++g) {
      const int c = grouped_[g];
      const CandidatePair& p = cands_[c];
      const bool feature_ok = p.feature >= 0 && p.feature < static_cast<int>(feature_use_.size());
      if (!feature_ok) continue;
      if (!options_.allow_shared_features && feature_use_[p.feature] > 0) continue;
      // Cross covariances C (2k x 2) with the pairings already in the hypothesis; X = L^-1 C.
      // Rows of X for level m depend only on the pairings at levels 0..m: cached per level.
      // The Schur complement S_p - X^T X and v = nu_p - X^T y are accumulated level by level;
      // after level m they give D^2 of the hypothesis cut to levels 0..m plus p, a lower bound
      // of the final D^2 (a Mahalanobis distance never shrinks when components are added), so
      // a pairing that fails the gate early costs no more levels.
      const int r0 = 2 * k;
      const double gate = gate_[k + 1];
      double s00 = p.S(0, 0), s01 = p.S(0, 1), s11 = p.S(1, 1);
      double v0 = p.innovation(0), v1 = p.innovation(1);
      bool rejected = false;
      for (int m = 0; m < k && !rejected; ++m) {
        CacheEntry& e = cache_[static_cast<size_t>(m) * cands_.size() + c];
        double* xm = &x_[4 * m];
        if (e.version != version_[m]) {
          const Mat2 cm = cov_.Cross(cands_[stack_[m]], p);
          for (int h = 0; h < 2; ++h) {
            const int r = 2 * m + h;
            double s0 = cm(h, 0), s1 = cm(h, 1);
            const double* lr = &l_[static_cast<size_t>(r) * dim_];
            for (int q = 0; q < r; ++q) {
              s0 -= lr[q] * x_[2 * q];
              s1 -= lr[q] * x_[2 * q + 1];
            }
            x_[2 * r] = s0 / lr[r];
            x_[2 * r + 1] = s1 / lr[r];
          }
          for (int i = 0; i < 4; ++i) e.x[i] = xm[i];
          e.version = version_[m];
        } else {
          for (int i = 0; i < 4; ++i) xm[i] = e.x[i];
        }
        for (int r = 2 * m; r < 2 * m + 2; ++r) {
          s00 -= x_[2 * r] * x_[2 * r];
          s01 -= x_[2 * r] * x_[2 * r + 1];
          s11 -= x_[2 * r + 1] * x_[2 * r + 1];
          v0 -= x_[2 * r] * y_[r];
          v1 -= x_[2 * r + 1] * y_[r];
        }
        if (m + 1 < k) rejected = !(ycum_[2 * m + 1] + Increment(s00, s01, s11, v0, v1) < gate);
      }
      if (rejected) continue;
      if (!(s00 > 0.0)) continue;
      const double l00 = std::sqrt(s00);
      const double l10 = s01 / l00;
      const double t = s11 - l10 * l10;
      if (!(t > 0.0)) continue;
      const double l11 = std::sqrt(t);
      const double y0 = v0 / l00;
      const double y1 = (v1 - l10 * y0) / l11;
      const double d2_new = d2 + y0 * y0 + y1 * y1;
      if (!(d2_new < gate)) continue;
      for (int r = 0; r < r0; ++r) {
        L(r0, r) = x_[2 * r];
        L(r0 + 1, r) = x_[2 * r + 1];
      }
      L(r0, r0) = l00;
      L(r0, r0 + 1) = 0.0;
      L(r0 + 1, r0) = l10;
      L(r0 + 1, r0 + 1) = l11;
      y_[r0] = y0;
      y_[r0 + 1] = y1;
      ycum_[r0] = d2 + y0 * y0;
      ycum_[r0 + 1] = d2_new;
      stack_[k] = c;
      version_[k] = ++version_counter_;
      current_pair_of_[j] = c;
      ++feature_use_[p.feature];
      Visit(level + 1, k + 1, d2_new);
      --feature_use_[p.feature];
      current_pair_of_[j] = -1;
      if (exhausted) return;
    }
    Visit(level + 1, k, d2);
  }

  const std::vector<CandidatePair>& cands_;
  const JointCovariance& cov_;
  const JcbbOptions& options_;
  std::vector<int> start_, grouped_;
  struct CacheEntry {
    uint64_t version = 0;
    double x[4];
  };
  std::vector<CacheEntry> cache_;
  std::vector<uint64_t> version_;
  uint64_t version_counter_ = 0;
  std::vector<int> order_;
  std::vector<double> gate_;
  std::vector<double> l_, y_, x_;
  std::vector<double> ycum_;  // ycum_[r]: sum of y_[0..r]^2
  std::vector<int> stack_;
  std::vector<int> current_pair_of_;
  std::vector<int> feature_use_;
  int dim_ = 0;
};

}  // namespace

double ChiSquareQuantile(double p, int dof) {
  if (dof <= 0) return 0.0;
  if (dof == 2) return -2.0 * std::log(1.0 - p);
  const double z = NormalQuantile(dof == 1 ? 0.5 * (1.0 + p) : p);
  if (dof == 1) return z * z;
  return WilsonHilferty(z, dof);
}

JcbbResult Jcbb(int num_observations, const std::vector<CandidatePair>& candidates,
                const JointCovariance& cov, const JcbbOptions& options) {
  JcbbResult result;
  result.feature_of.assign(num_observations, -1);
  result.pair_of.assign(num_observations, -1);
  result.ambiguous.assign(num_observations, false);
  Search search(num_observations, candidates, cov, options);
  search.Run();
  result.nodes = search.nodes;
  if (search.exhausted) {
    result.status = AssociationStatus::kBudgetExhausted;
    return result;
  }
  if (search.ties.empty()) return result;
  const auto best = std::min_element(search.ties.begin(), search.ties.end(),
                                     [](const auto& a, const auto& b) { return a.d2 < b.d2; });
  result.pairings = search.best_pairings;
  result.joint_d2 = best->d2;
  for (int j = 0; j < num_observations; ++j) {
    result.pair_of[j] = best->pair_of[j];
    result.feature_of[j] = best->pair_of[j] >= 0 ? candidates[best->pair_of[j]].feature : -1;
  }
  for (const TieHypothesis& h : search.ties) {
    if (&h == &*best || h.d2 - best->d2 >= options.ambiguity_margin) continue;
    for (int j = 0; j < num_observations; ++j) {
      const int fa = h.pair_of[j] >= 0 ? candidates[h.pair_of[j]].feature : -1;
      if (fa != result.feature_of[j]) {
        result.ambiguous[j] = true;
        result.status = AssociationStatus::kAmbiguous;
      }
    }
  }
  return result;
}

}  // namespace atlas
