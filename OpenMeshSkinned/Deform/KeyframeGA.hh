#pragma once
/** \file KeyframeGA.hh
 *  Key-frame extraction for an animation given as frames of positions (the deformation-analysis report,
 *  3.2): choose K of the F frames so that every frame is best rebuilt by linear interpolation, in time,
 *  between the chosen frames around it. The first and the last frame are always chosen (nothing could
 *  rebuild the frames before the first key or after the last).
 *
 *  The report's genetic algorithm: a chromosome is a binary string over the frames (1 = key frame);
 *  crossover 0.95, mutation 0.05, plus its shift mutation (a key frame moves to a neighbouring frame, and
 *  in 3 % of those to the better side); 80 % of the first population random, 20 % evenly spread; the best
 *  chromosome is copied into the next generation; the run ends when the best has not changed for
 *  `stall_generations` and half the population equals it. Choices the report leaves open, made here:
 *  parents are picked by binary tournament (the fitter of two, so fitness needs no scaling); every
 *  chromosome keeps exactly K ones (after crossover, surplus ones are cleared and missing ones set at
 *  random); the mutation swaps a key frame with a non-key frame, which keeps K.
 */

#include "OpenMeshSkinned/Deform/DeformationAnalysis.hh"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace OpenMeshSkinned {

/// The error of rebuilding frames by interpolation between key frames: sums of squared distances over
/// every vertex of every frame, computed per pair of consecutive keys once and remembered.
class InterpolationError {
public:
  InterpolationError(const std::vector<FramePoints>& frames, const std::vector<double>& times);
  size_t n_frames() const { return frames_.size(); }
  /// The frames strictly between key frames \p a < \p b, rebuilt from them.
  double segment(size_t a, size_t b) const;
  /// Every frame rebuilt from \p keys (sorted, first and last frame included).
  double total(const std::vector<size_t>& keys) const;

private:
  const std::vector<FramePoints>& frames_;
  const std::vector<double>& times_;
  mutable std::unordered_map<uint64_t, double> memo_;
};

struct KeyframeGaSettings {
  size_t population = 200;  ///< the report uses 1000; 200 finds the same answers on our tests, sooner
  double crossover = 0.95;
  double mutation = 0.05;
  double shift_mutation = 0.05;
  double best_direction = 0.03;  ///< share of shift mutations that take the better side
  size_t stall_generations = 100;
  size_t max_generations = 3000;
  uint64_t seed = 1;
};

struct KeyframeSelection {
  std::vector<size_t> frames;  ///< sorted
  double error = 0.0;          ///< InterpolationError::total
  size_t generations = 0;
};

/// The genetic algorithm. Throws std::invalid_argument unless 2 <= k <= frames.
KeyframeSelection select_keyframes_ga(const InterpolationError& err, size_t k, const KeyframeGaSettings& s = {});
/// k frames evenly spaced in index, both ends included.
KeyframeSelection select_keyframes_even(const InterpolationError& err, size_t k);
/// The best k frames, by dynamic programming over (last key, keys used): O(k F^2) segments, each
/// O(F V); a reference to judge the genetic algorithm by.
KeyframeSelection select_keyframes_optimal(const InterpolationError& err, size_t k);

}  // namespace OpenMeshSkinned
