#include "warp/garment_warp.h"

#include "core/errors.h"

#include <tbb/parallel_for.h>

#include <string>

namespace xparam {

WarpedGarment warp_garment(const TriangleSoup& garment, const GarmentBinding& binding, const WarpTarget& target,
                           const WarpSettings& settings) {
  WarpedGarment result;
  result.name = target.name;
  for (const int face : binding.face) {
    if (face >= static_cast<int>(target.body.triangles.size()))
      throw InputError(target.name + ": its image has " + std::to_string(target.body.triangles.size()) +
                       " faces but the garment is bound to face " + std::to_string(face) +
                       "; it is not an image of the template the garment was bound to");
  }
  result.vertices = place_garment(binding, target.body);
  result.against_surface = target.surface.has_value();
  const BodyDistance body(target.surface ? *target.surface : target.body);
  result.placed_penetration = penetration(result.vertices, body);
  if (settings.clearance) result.clearance = apply_clearance(result.vertices, garment.triangles, body, *settings.clearance);
  result.penetration = settings.clearance ? penetration(result.vertices, body) : result.placed_penetration;
  result.change = shape_change(garment.vertices, result.vertices, garment.triangles);
  return result;
}

std::vector<WarpedGarment> warp_garment_onto(const TriangleSoup& garment, const GarmentBinding& binding,
                                             const std::vector<WarpTarget>& targets, const WarpSettings& settings,
                                             const std::function<void(std::size_t, const WarpedGarment&)>& on_done,
                                             const SurfaceLoader& load_surface) {
  std::vector<WarpedGarment> results(targets.size());
  tbb::parallel_for(std::size_t{0}, targets.size(), [&](std::size_t i) {
    try {
      std::optional<TriangleSoup> surface = !targets[i].surface && load_surface ? load_surface(i) : std::nullopt;
      if (surface) {
        WarpTarget with_surface{targets[i].name, targets[i].body, std::move(surface)};
        results[i] = warp_garment(garment, binding, with_surface, settings);
      } else {
        results[i] = warp_garment(garment, binding, targets[i], settings);
      }
    } catch (const Error& e) {
      results[i] = WarpedGarment{};
      results[i].name = targets[i].name;
      results[i].error = e.what();
    }
    if (on_done) on_done(i, results[i]);
  });
  return results;
}

}  // namespace xparam
