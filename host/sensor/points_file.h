// points_file.h — sensor points in the format daylighting tools already use: Radiance's
// `x y z dx dy dz` per line (what `rtrace -I` reads), in the scene's coordinates (metres, y up,
// as glTF), the direction the side the point faces. Blank lines and lines starting with '#' are
// skipped; any other line must hold exactly six finite numbers and a non-zero direction, or the
// file is refused with its line number. Each point becomes a square cell centred on it, facing
// its direction, of side `side_m` -- or, when that is not given, of the points' own spacing: the
// median distance from each point to its nearest neighbour (points of a regular grid then tile
// the plane they lie in).
#pragma once

#include <optional>
#include <string>

#include "sensor/sensor_set.h"

namespace fen {

void addPointsSensor(SensorSet& set, const std::string& path, std::optional<double> side_m);

}  // namespace fen
