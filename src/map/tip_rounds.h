#pragma once
/// \file
/// The rounds of helper anchors at protrusion tips of map_pair (map/pair_mapping.h,
/// PairSettings::extremity_anchors; ARCHITECTURE "Helper anchors at protrusion tips"), for its
/// translation unit only: tips found on each mesh and matched through the map before, by their
/// landmark's cell and by their distances, small toes in rows beside them, then a whole map through
/// them, or that map pulled onto them when it carries them already, and the retries of doubtful
/// matches.

#include "map/whole_maps.h"

#include <optional>

namespace xparam::pair_maps {

// A map through `current`'s anchors plus helper anchors at the tips of unanchored protrusions
// matched through it (PairSettings::extremity_anchors), or `current` pulled onto them, when it is
// better; nothing otherwise. With PairSettings::tip_rows, small toes among the tips, and the round
// made again without them when it finds no better map with them.
std::optional<AnchoredMap> with_extremity_anchors(const PairInputs& in, const AnchoredMap& current,
                                                  PairSeconds& seconds);

}  // namespace xparam::pair_maps
