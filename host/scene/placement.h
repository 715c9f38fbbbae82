// Placement: bodies put in the scene's cube without overlapping enclosing spheres (place_bodies), and the scenes'
// random draws (placement.cpp).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

namespace voxcd {

struct Scene;

// Places counts[i] bodies of scene.types[i] in the cube [0, scene.side]^3, type by type, appending them to
// scene.bodies, with non-overlapping enclosing spheres, random orientations, velocities of up to `speed` times the
// type's radius per frame in a random direction and spins of up to `spin` radians per frame. Deterministic for a
// seed. First at random (random sequential addition: up to 10,000 uniform tries a body, checked against the
// bodies placed so far through a uniform grid of cells at least as wide as the largest sphere, so O(1) a try);
// if a body finds no place, or the tries of all bodies pass 10^6 + 4 per body, again from the start on a
// lattice: the densest of a face-centred cubic and a simple cubic lattice in the cube, spread as wide as the
// count allows, N of its sites taken at random and each body jittered within the spacing's slack. The lattice
// treats every sphere as the largest. PlacementError (errors.h) when even the lattice at the closest spacing has too
// few sites (`capacity` of them).
void place_bodies(Scene& scene, const std::vector<uint64_t>& counts, double speed, double spin, uint64_t seed);

// The scenes' random draws (a uniform rotation; a uniform unit direction), one definition so that scene files
// place bodies exactly as the built-in scene does.
Eigen::Quaterniond scene_rotation(std::mt19937_64& rng);
// How many spheres of radius r place_bodies' lattice fits in the cube [0, side]^3 at the closest spacing (2r)
// (0 when one does not fit); the most bodies it places whatever the seed.
uint64_t lattice_capacity(double side, double r);
Eigen::Vector3d scene_direction(std::mt19937_64& rng);

}  // namespace voxcd
