#include "OpenMeshSkinned/Deform/KeyframeGA.hh"

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

namespace OpenMeshSkinned {

InterpolationError::InterpolationError(const std::vector<FramePoints>& frames, const std::vector<double>& times)
    : frames_(frames), times_(times) {
  if (frames.size() != times.size()) throw std::invalid_argument("one time per frame");
}

double InterpolationError::segment(size_t a, size_t b) const {
  const uint64_t key = uint64_t(a) << 32 | uint64_t(b);
  if (auto it = memo_.find(key); it != memo_.end()) return it->second;
  double e = 0.0;
  const double span = times_[b] - times_[a];
  for (size_t f = a + 1; f < b; ++f) {
    const double s = span > 0.0 ? (times_[f] - times_[a]) / span : 0.0;
    for (size_t v = 0; v < frames_[f].size(); ++v)
      e += (frames_[f][v] - ((1.0 - s) * frames_[a][v] + s * frames_[b][v])).squaredNorm();
  }
  memo_.emplace(key, e);
  return e;
}

double InterpolationError::total(const std::vector<size_t>& keys) const {
  double e = 0.0;
  for (size_t i = 1; i < keys.size(); ++i) e += segment(keys[i - 1], keys[i]);
  return e;
}

namespace {

using Genes = std::vector<char>;

std::vector<size_t> keys_of(const Genes& g) {
  std::vector<size_t> k;
  for (size_t i = 0; i < g.size(); ++i)
    if (g[i]) k.push_back(i);
  return k;
}

void check(const InterpolationError& err, size_t k) {
  if (k < 2 || k > err.n_frames())
    throw std::invalid_argument("key frames: need 2 to " + std::to_string(err.n_frames()) + ", asked " +
                                std::to_string(k));
}

class Ga {
public:
  Ga(const InterpolationError& err, size_t k, const KeyframeGaSettings& s)
      : err_(err), n_(err.n_frames()), k_(k), s_(s), rng_(s.seed) {}

  KeyframeSelection run() {
    std::vector<Genes> pop;
    for (size_t i = 0; i < std::max<size_t>(2, s_.population); ++i) pop.push_back(i % 5 == 4 ? spread() : random());
    std::vector<double> fit = evaluate(pop);
    size_t best = argmin(fit), stall = 0, gen = 0;
    Genes best_genes = pop[best];
    double best_error = fit[best];
    for (; gen < s_.max_generations; ++gen) {
      std::vector<Genes> next = {best_genes};
      while (next.size() < pop.size()) {
        Genes a = pop[tournament(fit)], b = pop[tournament(fit)];
        if (unit_(rng_) < s_.crossover) crossover(a, b);
        for (Genes* c : {&a, &b}) {
          if (unit_(rng_) < s_.mutation) swap_mutation(*c);
          if (unit_(rng_) < s_.shift_mutation) shift_mutation(*c);
          if (next.size() < pop.size()) next.push_back(std::move(*c));
        }
      }
      pop = std::move(next);
      fit = evaluate(pop);
      best = argmin(fit);
      if (fit[best] < best_error) {
        best_error = fit[best];
        best_genes = pop[best];
        stall = 0;
      } else if (++stall >= s_.stall_generations &&
                 2 * size_t(std::count(pop.begin(), pop.end(), best_genes)) >= pop.size()) {
        ++gen;
        break;
      }
    }
    return {keys_of(best_genes), best_error, gen};
  }

private:
  // Ends fixed, k - 2 of the inner frames at random.
  Genes random() {
    Genes g(n_, 0);
    g[0] = g[n_ - 1] = 1;
    std::vector<size_t> inner(n_ - 2);
    std::iota(inner.begin(), inner.end(), 1);
    std::shuffle(inner.begin(), inner.end(), rng_);
    for (size_t i = 0; i + 2 < k_; ++i) g[inner[i]] = 1;
    return g;
  }
  // The report's seeded chromosomes (keys spread out, no two neighbours): k evenly spaced frames, each
  // inner one jittered by up to half a spacing.
  Genes spread() {
    Genes g(n_, 0);
    g[0] = g[n_ - 1] = 1;
    const double step = double(n_ - 1) / double(k_ - 1);
    std::uniform_real_distribution<double> jitter(-0.5 * step, 0.5 * step);
    for (size_t i = 1; i + 1 < k_; ++i) {
      const long f = std::clamp<long>(std::lround(i * step + jitter(rng_)), 1, long(n_) - 2);
      g[size_t(f)] = 1;
    }
    repair(g);
    return g;
  }
  // Exactly k ones, the ends among them.
  void repair(Genes& g) {
    g[0] = g[n_ - 1] = 1;
    std::vector<size_t> ones, zeros;
    for (size_t i = 1; i + 1 < n_; ++i) (g[i] ? ones : zeros).push_back(i);
    while (ones.size() + 2 > k_) {
      const size_t j = std::uniform_int_distribution<size_t>(0, ones.size() - 1)(rng_);
      g[ones[j]] = 0;
      ones.erase(ones.begin() + long(j));
    }
    while (ones.size() + 2 < k_) {
      const size_t j = std::uniform_int_distribution<size_t>(0, zeros.size() - 1)(rng_);
      g[zeros[j]] = 1;
      ones.push_back(zeros[j]);
      zeros.erase(zeros.begin() + long(j));
    }
  }
  void crossover(Genes& a, Genes& b) {
    const size_t cut = std::uniform_int_distribution<size_t>(1, n_ - 1)(rng_);
    std::swap_ranges(a.begin() + long(cut), a.end(), b.begin() + long(cut));
    repair(a);
    repair(b);
  }
  void swap_mutation(Genes& g) {
    if (k_ == 2 || k_ == n_) return;
    std::vector<size_t> ones, zeros;
    for (size_t i = 1; i + 1 < n_; ++i) (g[i] ? ones : zeros).push_back(i);
    std::swap(g[ones[std::uniform_int_distribution<size_t>(0, ones.size() - 1)(rng_)]],
              g[zeros[std::uniform_int_distribution<size_t>(0, zeros.size() - 1)(rng_)]]);
  }
  void shift_mutation(Genes& g) {
    std::vector<size_t> movable;
    for (size_t i = 1; i + 1 < n_; ++i)
      if (g[i] && (!g[i - 1] || !g[i + 1])) movable.push_back(i);
    if (movable.empty()) return;
    const size_t f = movable[std::uniform_int_distribution<size_t>(0, movable.size() - 1)(rng_)];
    auto moved = [&](size_t to) {
      Genes h = g;
      h[f] = 0;
      h[to] = 1;
      return h;
    };
    std::vector<size_t> to;
    if (!g[f - 1] && f - 1 > 0) to.push_back(f - 1);
    if (!g[f + 1] && f + 1 < n_ - 1) to.push_back(f + 1);
    if (to.empty()) return;
    size_t pick = to[std::uniform_int_distribution<size_t>(0, to.size() - 1)(rng_)];
    if (to.size() == 2 && unit_(rng_) < s_.best_direction)
      pick = err_.total(keys_of(moved(to[0]))) <= err_.total(keys_of(moved(to[1]))) ? to[0] : to[1];
    g = moved(pick);
  }
  size_t tournament(const std::vector<double>& fit) {
    std::uniform_int_distribution<size_t> pick(0, fit.size() - 1);
    const size_t a = pick(rng_), b = pick(rng_);
    return fit[a] <= fit[b] ? a : b;
  }
  std::vector<double> evaluate(const std::vector<Genes>& pop) const {
    std::vector<double> f;
    for (const Genes& g : pop) f.push_back(err_.total(keys_of(g)));
    return f;
  }
  static size_t argmin(const std::vector<double>& f) {
    return size_t(std::min_element(f.begin(), f.end()) - f.begin());
  }

  const InterpolationError& err_;
  size_t n_, k_;
  KeyframeGaSettings s_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
};

}  // namespace

KeyframeSelection select_keyframes_ga(const InterpolationError& err, size_t k, const KeyframeGaSettings& s) {
  check(err, k);
  if (k == err.n_frames() || k == 2) {
    std::vector<size_t> all(k == 2 ? 0 : k);
    std::iota(all.begin(), all.end(), 0);
    if (k == 2) all = {0, err.n_frames() - 1};
    return {all, err.total(all), 0};
  }
  return Ga(err, k, s).run();
}

KeyframeSelection select_keyframes_even(const InterpolationError& err, size_t k) {
  check(err, k);
  std::vector<size_t> keys;
  for (size_t i = 0; i < k; ++i)
    keys.push_back(size_t(std::lround(double(i) * double(err.n_frames() - 1) / double(k - 1))));
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return {keys, err.total(keys), 0};
}

KeyframeSelection select_keyframes_optimal(const InterpolationError& err, size_t k) {
  check(err, k);
  const size_t n = err.n_frames();
  const double inf = std::numeric_limits<double>::infinity();
  // cost[m][j]: the least error of frames 0..j with m + 1 keys, the last at j; from[m][j]: the key before.
  std::vector<std::vector<double>> cost(k, std::vector<double>(n, inf));
  std::vector<std::vector<size_t>> from(k, std::vector<size_t>(n, 0));
  cost[0][0] = 0.0;
  for (size_t m = 1; m < k; ++m)
    for (size_t j = m; j < n; ++j)
      for (size_t i = m - 1; i < j; ++i) {
        if (cost[m - 1][i] == inf) continue;
        const double c = cost[m - 1][i] + err.segment(i, j);
        if (c < cost[m][j]) cost[m][j] = c, from[m][j] = i;
      }
  std::vector<size_t> keys = {n - 1};
  for (size_t m = k - 1, j = n - 1; m > 0; --m) keys.push_back(j = from[m][j]);
  std::reverse(keys.begin(), keys.end());
  return {keys, cost[k - 1][n - 1], 0};
}

}  // namespace OpenMeshSkinned
