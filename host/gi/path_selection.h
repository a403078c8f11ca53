// The instant cache's light paths kept for the view: whole candidate paths kept with
// probabilities from their VPLs' view importance (gi/vpl_importance.h), by a systematic
// sample a path subset over its candidates sorted by where in the view their light lands,
// so that each part of the view (a cell of the sort's Morton order) keeps its share of a
// subset's paths to within one (docs/instant-caching.md §2).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gi/light_paths.h"

namespace tessera {

/// The sort key of candidate paths: the Morton code (21 bits an axis) of each path's
/// centre, the mean of its VPLs' `where` (vpl_view_importance, 3 floats a VPL in path
/// order) weighed by their `importance`, over the box of the centres of all `candidates`;
/// UINT64_MAX for a path of no importance (VPLs with no finite `where` do not count). One
/// key a path. Throws std::invalid_argument unless `where` has 3 floats per `importance`.
std::vector<uint64_t> path_view_keys(const std::vector<LightPath>& candidates, const std::vector<float>& importance,
                                     const std::vector<float>& where);

/// Keeps candidate path j of `candidates` with p_j = path_keep_probabilities of its
/// importance (the sum of its VPLs' Φ_i, `importance` one float per VPL of the candidates
/// in path order), K = `oversampling`, and returns the kept paths in candidate order with
/// weight 1/p_j and their VPLs' flux multiplied by it. Each run of `run` consecutive
/// candidates (an instant cache subset, docs/instant-caching.md §2b; the last may be
/// shorter) is one systematic sample (systematic_sample) over its paths sorted by
/// path_view_keys(candidates, importance, where), then by index: each path is kept with
/// probability exactly p_j, so the estimate is unbiased for any importance, and the paths
/// of a run whose light lands in one part of the view (a run of the sorted order: a cell
/// of the Morton order) keep their share Σ p_j to within one, where independent decisions
/// left that count its binomial noise; a region of the image that spans r such cells is
/// within r. The sample's offset is the counter-based generator keyed by `seed_mix` and the
/// 64-bit index of the run's first candidate. `run` 0 counts as 1 (independent decisions).
/// A whole path is kept or dropped, so that the temporal cache can re-trace a kept path
/// with its weight when moving geometry invalidates it; the weight is fixed when the path
/// is drawn.
/// A decision depends on the p and keys of the run's paths sorted before it: importance
/// that differs (another backend's view points, a duplicated surface in view) may keep
/// other paths, an estimate as good but not the same samples.
std::vector<LightPath> select_paths(std::vector<LightPath>& candidates, const std::vector<float>& importance,
                                    const std::vector<float>& where, size_t run, uint32_t oversampling,
                                    uint32_t seed_mix);

}  // namespace tessera
