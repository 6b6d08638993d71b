#pragma once
// How much of the scene a surface point sees: the mean, over the scene's
// surface area, of the area visible from a point, as a share of the whole
// scene's area. One room: most of it (0.5 to 0.9). A building floor of 60
// rooms: about a sixtieth. The refinement thresholds (epsilon's reference
// power and the area threshold) are taken relative to what a point sees, not
// to the whole scene, so that each room of a large scene is refined as it
// would be alone (Refiner::settings().referencePower).

#include <vector>

#include "geometry/RayCaster.h"
#include "radiosity/Scene.h"

namespace rad {

// Points (area-weighted over the polygons) and directions (uniform over
// each point's hemisphere) are fixed sequences, so a scene always gets the
// same answer.
inline constexpr int kSurroundingsPoints = 4096;
inline constexpr int kSurroundingsRays = 4;  // per point

struct Surroundings {
    // The share, in [0, 1], estimated from kSurroundingsPoints x
    // kSurroundingsRays nearest hits: a ray from x meeting a surface at
    // distance d, at an angle theta to its normal, stands for
    // 2 pi d^2 / |cos theta| of visible area (uniform hemisphere sampling),
    // |cos theta| at least 0.2 (a grazing hit stands for no more than five
    // times its head-on area).
    double visibleShare = 1.0;
    // The share of those rays that met nothing: they left the scene.
    double escapedShare = 0.0;
};
// `rays` holds the scene's polygons (either layer).
Surroundings measureSurroundings(const Scene& scene, const RayCaster& rays);

// The same from kObjectPoints points on each object's own polygons (by area;
// a share still of the whole scene's area), one per object (an object with
// no polygons gets the defaults).
inline constexpr int kObjectPoints = 64;
std::vector<Surroundings> measureObjectSurroundings(const Scene& scene, const RayCaster& rays);

// A scene whose points see the sky in more than this share of their rays
// is open: what they see little of is not a room around them (a ground
// plane 100 m wide with a box on it: each point sees 0.09% of the scene),
// and its thresholds stay the whole scene's.
inline constexpr double kOpenShare = 0.2;

// The thresholds' scale (EngineSettings::localThresholds): 1 for an open
// scene or a room (its points see kRoomShare or more of it); else the
// visible share over kRoomShare, rounded down to a power of two, so that
// moving an object (which changes the estimate a little) leaves the
// thresholds of a from-scratch solve where the solve's were.
double thresholdScale(const Surroundings& surroundings);

// In an open scene (which keeps 1), the default area threshold's scale per
// object. The objects closed in from the sky (no more than kOpenShare of
// their rays leave) are the scene's closed part, and take thresholdScale of
// its mean share (by area), as a closed scene's rooms take the scene's; the
// others keep 1. A room on a site plane 1 km wide sees its own walls, not
// the sky, and is meshed about as it would be alone (with the plane's area
// in the scene's, 2e-5 of it is 20 m^2: its walls, floor and furniture
// could not be divided at all). The reference power stays the scene's: the
// share of the emitted power a point sees is not measured.
std::vector<double> objectAreaScales(const Scene& scene, const std::vector<Surroundings>& objects);

// Both, measured with `rays` (the scene's polygons): the scene's scale (of
// the reference power, and of the default area threshold), and in an open
// scene each object's for its area threshold (empty: the scene's for all).
struct ThresholdScales {
    double scene = 1.0;
    std::vector<double> objectArea;
};
ThresholdScales measureThresholdScales(const Scene& scene, const RayCaster& rays);

}  // namespace rad
