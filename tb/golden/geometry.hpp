// The golden model's view of a memory image: the image's sections decoded into Geometry<T>, and
// the scene's triangles as a soup for the reference engines.
#pragma once

#include <vector>

#include "embree_engine.hpp"
#include "image.hpp"
#include "scene.hpp"
#include "trace.hpp"

namespace rc {

// Decodes the image's nodes, lists, transforms, shading records and materials. Throws
// rc::scene::Error when the image's number format is not T's or its root is not node 0.
template <class T>
Geometry<T> load_geometry(const scene::SceneImage& img);

// The scene's triangles in OBJ order (after fan triangulation), with their diffuse colours.
std::vector<SoupTriangle> triangle_soup(const scene::Scene& s);
// The scene's lights for the reference engine, in the scene's order.
std::vector<SoupLight> soup_lights(const scene::Scene& s);

}  // namespace rc
