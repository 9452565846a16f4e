// CGAL 5.5's isotropic remeshing of a triangle mesh with its sharp edges
// constrained, for bench_peers. It lives in its own translation unit
// (cgal_remesh.cpp) because CGAL's exact-predicates kernel needs GCC's
// -frounding-math, which must not slow the other peers' inlined code.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

struct CgalRemeshing {
    // The input's sharp edges by detect_sharp_edges (border edges and those
    // whose face normals differ by more than the angle), as vertex pairs
    // (i, j), i < j, sorted.
    std::vector<std::array<int32_t, 2>> sharp;
    // The first run's output mesh.
    std::vector<double> xyz;
    std::vector<int32_t> tris;
    // Seconds of each run, isotropic_remeshing alone.
    std::vector<double> seconds;
};

// Remeshes the mesh (`xyz`: 3 per vertex, `tris`: 3 per triangle) `reps`
// times from scratch at target edge length `h`, `iterations` iterations,
// with the edges sharper than `angle` degrees constrained.
CgalRemeshing cgal_isotropic_remeshing(const std::vector<double>& xyz, const std::vector<int32_t>& tris, double angle, double h,
                                       unsigned iterations, int reps);
