#pragma once
// Small scenes built in code for known-answer tests.

#include <string>

#include "radiosity/Scene.h"

namespace rad::test {

// Adds a material and returns its index.
std::uint32_t addMaterial(Scene& scene, glm::dvec3 reflectance, glm::dvec3 emission, std::string name = "m");

// Adds an object made of quads given as 4 corners each (counter-clockwise
// seen from the front). Returns the object index.
std::uint32_t addQuadObject(Scene& scene, const std::string& name, std::uint32_t material,
                            const std::vector<std::array<glm::dvec3, 4>>& quads, bool dynamic = false);

// An axis-aligned box [lo, hi] with its six faces pointing inwards, or
// outwards for a solid block.
std::vector<std::array<glm::dvec3, 4>> boxFaces(glm::dvec3 lo, glm::dvec3 hi, bool inward);

// Unit square emitter (E = 1, rho = 0) 1 m above a unit square receiver of
// reflectance rho, facing each other.
Scene parallelSquares(double rho);
// Unit square receiver on the floor [0,1]x[0,1] (y = 0, facing up) and a unit
// square emitter in the plane x = 0 sharing the edge z in [0,1], facing +x.
Scene perpendicularSquares(double rho);
// Closed unit cube, all faces emitting E = 1 with reflectance rho, inwards.
Scene closedBox(double rho);

// A closed 4 x 3 x 4 m room (inward faces), a light on the ceiling and a
// dynamic block ("block", six outward faces) above the floor; every vertex
// times `scale`; `blockOffset` moves the block before scaling.
Scene roomWithBlock(double scale = 1.0, glm::dvec3 blockOffset = glm::dvec3(0.0));

// A corridor (4 x 2.5 x 2 m, a ceiling light) and a dark room behind a 0.1 m
// wall, joined by a 1 x 2 m doorway. The door ("door", marked dynamic when
// `doorDynamic`) closes it, where `placement` says:
// - GapInFront: on the corridor side 2 mm off the wall, overlapping the
//   opening by 5 cm on the sides and the top;
// - AgainstTheWall: the same, touching the wall;
// - InTheReveal: 4 cm thick, filling the opening halfway through the wall,
//   its edges on the reveal's faces.
// Closed, no straight line reaches the dark room. Every object of the dark
// room is named "dark-...". doorHinge() is the hinge line of the door in
// front of the wall (axis +y): a positive turn about it opens the door into
// the corridor.
// Where the closed door stands: 2 mm in front of the wall (the corridor's
// side), against it, filling the opening in the reveal, or 2 mm behind the
// wall on the dark room's side.
enum class DoorPlacement { GapInFront, AgainstTheWall, InTheReveal, GapBehind };
Scene doorwayScene(bool doorDynamic = true, DoorPlacement placement = DoorPlacement::GapInFront);
glm::dvec3 doorHinge();
// Two closed rooms, 4 x 2.6 x 4 m, white (reflectance 0.85), joined by an
// opening of 0.8 x 0.6 m high in the 20 cm wall between them: "lit-" under a
// ceiling panel, "dark-" (a block on its floor) lit only through the
// opening, about a hundredth as brightly.
Scene roomsThroughAnOpening();

std::string sourcePath(const std::string& relative);
// The shipped scenes the tests use.
inline const std::string kCornell = sourcePath("scenes/cornell-box.gltf");
Scene office();  // scenes/office.gltf, loaded

}  // namespace rad::test
