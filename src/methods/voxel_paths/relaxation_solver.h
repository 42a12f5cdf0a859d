// relaxation_solver.h: shortest optical paths n(v) on the GPU by iterated parallel relaxation (Bellman-Ford
// sweeps, src/methods/voxel_paths/shaders/relax.comp) over the graph of voxel_dijkstra.h, all three colour bands in one
// sweep. Sweeps run in batches of `check_every`; after each batch the "changed" flag is read back and the solver
// stops when a whole batch lowered nothing (converged: the result equals Dijkstra's up to float rounding) or
// after `max_iterations` sweeps.
#pragma once
#include <span>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/shader_program.h"
#include "methods/voxel_paths/voxel_dijkstra.h"
#include "methods/voxel_paths/voxel_grid.h"

namespace lucent::methods::voxel_paths {

// How sweeps choose their voxels: every inside voxel (kSweep), or only the 4^3 blocks next to a block that
// changed in the previous sweep (kActiveBlocks; relax.comp explains why the result is the same).
enum class RelaxationSchedule { kSweep, kActiveBlocks };

struct RelaxationStats {
  int iterations = 0;      // sweeps run
  bool converged = false;  // the last batch changed nothing
};

class RelaxationSolver {
 public:
  explicit RelaxationSolver(RelaxationSchedule schedule = RelaxationSchedule::kActiveBlocks);
  ~RelaxationSolver();
  RelaxationSolver(const RelaxationSolver&) = delete;
  RelaxationSolver& operator=(const RelaxationSolver&) = delete;

  // Sets every voxel to kUnreached except the sources (uploaded from the CPU).
  void reset(const VoxelGrid& grid, std::span<const VoxelSource> sources);
  // Sizes the distance buffer for `grid` (contents undefined) for a GPU pass to initialize.
  void resize(const VoxelGrid& grid);
  // Relaxes until converged or max_iterations; labels as the Voxelizer fills them, coefficients (vec4 per voxel,
  // rgb sigma_t) as CoefficientField fills them.
  RelaxationStats solve(const VoxelGrid& grid, GLuint labels_buffer, GLuint coefficients_buffer, int check_every,
                        int max_iterations);

  GLuint distances_buffer() const { return distances_; }  // vec4 per voxel, rgb: n(v)
  std::vector<glm::vec3> read_distances() const;

 private:
  RelaxationSchedule schedule_;
  gpu::ShaderProgram program_;
  GLuint distances_ = 0, changed_ = 0, blocks_[2] = {0, 0};
  std::size_t voxel_count_ = 0, block_count_ = 0;
};

}  // namespace lucent::methods::voxel_paths
