#pragma once
/// The private state of LimitSurface (limit_surface.hpp), shared by the files that
/// implement it: limit_surface.cpp (construction, evaluation, walking) and
/// limit_surface_self_test.cpp (the check of OpenSubdiv's second-derivative stencils).
#include <opensubdiv/bfr/surface.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "tightfit/subdiv/limit_projector.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit {

struct LimitSurface::Impl {
  Triangles faces;
  std::vector<OpenSubdiv::Bfr::Surface<double>> surfaces;
  // Control points of face f (base-vertex indices, may repeat): cp_index[cp_offset[f] ..
  // cp_offset[f+1]).
  std::vector<int> cp_offset;
  std::vector<int> cp_index;
  // Slot of each control point in the face's list of unique indices. Slots are
  // numbered by first occurrence, so slot(k) ≤ k and accumulation can run in place.
  std::vector<int> cp_slot;
  std::vector<std::uint8_t> cp_first;  // first occurrence of its index in the face
  std::vector<int> unique_offset;
  std::vector<int> unique_index;
  std::vector<std::uint8_t> ev_corners;      // bit k: corner k has valence ≠ 6
  std::vector<std::uint8_t> has_duplicates;  // a control index repeats in the face
  std::vector<std::uint8_t> irregular;       // Bfr surface is a patch tree
  std::vector<EdgeMap> edge_maps;            // 3 per face
  int max_control_points = 0;
  int max_valence = 0;
  int patch_tree_depth = 0;

  // Projection cache for LimitSurface::project without a hint.
  std::mutex projector_mutex;
  std::shared_ptr<const LimitProjector> projector;
};

}  // namespace tightfit
