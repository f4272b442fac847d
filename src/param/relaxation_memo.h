#pragma once
/// \file
/// Patch relaxations (param/map_relaxation.h) made once per exact input. The maps of one pair
/// (later layouts, rounds of tips, a rival without a tip) share most of their patches: a patch
/// away from the anchors that changed has the same triangles, positions and start in each, and
/// relaxing it again gives the same result bit for bit (the relaxation is deterministic). Measured
/// on FAUST 000/030 with the 29 anthropometric landmarks (6 maps, session 28): 327 of the pair's
/// 565 relaxations repeated one made before, half of the relaxations' work.
///
/// The key is the inputs' bytes, compared whole (no hash is trusted alone), so a result is reused
/// only for exactly the same input. Safe to call from several threads at once.

#include "param/map_relaxation.h"
#include "param/patch_parameterization.h"

#include <Eigen/Core>

#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace xparam {

class RelaxationMemo {
 public:
  /// relax_patch_map(source, initial_uv, target, scale, settings); `target.locator` must be a
  /// PointLocator over *target.uv and target.patch->triangles (it is not part of the key).
  MapRelaxationResult relax_patch_map(const DiskPatch& source, const std::vector<Eigen::Vector2d>& initial_uv,
                                      const TargetPatchView& target, double scale,
                                      const MapRelaxationSettings& settings);

  /// relax_patch_parameterization(patch, uv, settings).
  MapRelaxationResult relax_patch_parameterization(const DiskPatch& patch,
                                                   const std::vector<Eigen::Vector2d>& uv,
                                                   const MapRelaxationSettings& settings);

  int reused() const;  ///< calls answered from the memo

 private:
  template <typename Relax>
  MapRelaxationResult remembered(std::string key, const Relax& relax);

  mutable std::mutex mutex_;
  std::unordered_map<std::string, MapRelaxationResult> results_;
  int reused_ = 0;
};

}  // namespace xparam
