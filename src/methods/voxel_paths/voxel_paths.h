// voxel_paths.h: the "voxel-paths" method: subsurface scattering as the shortest optical path through a solid
// voxelization of the translucent objects (after "Real-time rendering of heterogeneous translucent materials
// using Dijkstra's algorithm", shared/papers/voxel-dijkstra-heterogeneous-sss.txt). Per frame: the light
// G-buffer (the paper's reflective shadow map), GPU voxelization (voxelizer.h), lit voxels initialized to
// -ln(F_t P) (eqs. 2-3), shortest optical paths by parallel relaxation (relaxation_solver.h; verified against
// the CPU Dijkstra of voxel_dijkstra.h), exp(-n) into a 3D texture and surface shading F_t exp(-n) / pi (eq. 1).
// Limits: point and spot lights scatter only from the outside of the objects (a light inside one sees back faces);
// deforming objects are voxelized undeformed; blob surfaces are refused. See docs/methods/voxel-paths.md.
#pragma once
#include <span>

#include "lucent/params.h"
#include "methods/method.h"

namespace lucent::methods {

std::span<const ParamDecl> voxel_paths_params();
std::unique_ptr<Method> create_voxel_paths(const Scene& scene, const render::SceneGpu& scene_gpu);

}  // namespace lucent::methods
