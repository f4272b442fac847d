#include "param/relaxation_memo.h"

#include <array>
#include <type_traits>
#include <utility>

namespace xparam {
namespace {

// Appends the bytes of trivially copyable values to a key, after their size (so that two vectors
// cannot run into each other).
template <typename T>
void append(std::string& key, const T* data, std::size_t count) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::size_t size = count * sizeof(T);
  key.append(reinterpret_cast<const char*>(&size), sizeof size);
  key.append(reinterpret_cast<const char*>(data), size);
}

template <typename T>
void append(std::string& key, const std::vector<T>& values) {
  append(key, values.data(), values.size());
}

// A vector of Eigen's fixed-size vectors is one packed array of doubles.
template <int N>
void append(std::string& key, const std::vector<Eigen::Matrix<double, N, 1>>& points) {
  static_assert(sizeof(Eigen::Matrix<double, N, 1>) == N * sizeof(double));
  append(key, points.empty() ? nullptr : points.front().data(), N * points.size());
}

template <typename T>
void append_value(std::string& key, const T& value) {
  append(key, &value, 1);
}

void append(std::string& key, const MapRelaxationSettings& settings) {
  append_value(key, settings.max_iterations);
  append_value(key, settings.relative_tolerance);
  append_value(key, settings.min_mean_energy);
}

// What relax_patch_map reads of a patch (not its polygon: the boundary stays where it is).
void append_mesh(std::string& key, const DiskPatch& patch) {
  append(key, patch.triangles);
  append(key, patch.positions);
  append(key, patch.boundary_loop);
}

}  // namespace

template <typename Relax>
MapRelaxationResult RelaxationMemo::remembered(std::string key, const Relax& relax) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto found = results_.find(key);
    if (found != results_.end()) {
      ++reused_;
      return found->second;
    }
  }
  // Outside the lock: two threads may make the same relaxation at once, with the same result.
  MapRelaxationResult result = relax();
  const std::lock_guard<std::mutex> lock(mutex_);
  results_.emplace(std::move(key), result);
  return result;
}

MapRelaxationResult RelaxationMemo::relax_patch_map(const DiskPatch& source,
                                                    const std::vector<Eigen::Vector2d>& initial_uv,
                                                    const TargetPatchView& target, double scale,
                                                    const MapRelaxationSettings& settings) {
  std::string key(1, 'M');
  append(key, settings);
  append_value(key, scale);
  append_mesh(key, source);
  append(key, initial_uv);
  append(key, target.patch->triangles);
  append(key, target.patch->positions);
  append(key, *target.uv);
  return remembered(std::move(key),
                    [&] { return xparam::relax_patch_map(source, initial_uv, target, scale, settings); });
}

MapRelaxationResult RelaxationMemo::relax_patch_parameterization(const DiskPatch& patch,
                                                                 const std::vector<Eigen::Vector2d>& uv,
                                                                 const MapRelaxationSettings& settings) {
  std::string key(1, 'P');
  append(key, settings);
  append_mesh(key, patch);
  append(key, patch.polygon);
  append(key, uv);
  return remembered(std::move(key),
                    [&] { return xparam::relax_patch_parameterization(patch, uv, settings); });
}

int RelaxationMemo::reused() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return reused_;
}

}  // namespace xparam
