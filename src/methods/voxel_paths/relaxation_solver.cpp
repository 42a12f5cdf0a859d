// relaxation_solver.cpp: see relaxation_solver.h.
#include "methods/voxel_paths/relaxation_solver.h"

#include "gpu/gl_debug.h"

namespace lucent::methods::voxel_paths {

RelaxationSolver::RelaxationSolver(RelaxationSchedule schedule)
    : schedule_(schedule),
      program_(gpu::ShaderProgram::compute(
          "methods/voxel_paths/shaders/relax.comp",
          shader_defines() + (schedule == RelaxationSchedule::kActiveBlocks ? "#define VOXEL_ACTIVE_BLOCKS 1\n" : ""))) {
  GLuint buffers[4];
  glCreateBuffers(4, buffers);
  distances_ = buffers[0], changed_ = buffers[1], blocks_[0] = buffers[2], blocks_[1] = buffers[3];
  glNamedBufferData(distances_, 16, nullptr, GL_DYNAMIC_DRAW);
  glNamedBufferData(changed_, 4, nullptr, GL_DYNAMIC_READ);
  for (GLuint b : blocks_) glNamedBufferData(b, 4, nullptr, GL_DYNAMIC_DRAW);
  gpu::label_object(GL_BUFFER, distances_, "voxel-paths distances");
  gpu::label_object(GL_BUFFER, changed_, "voxel-paths changed flag");
  gpu::label_object(GL_BUFFER, blocks_[0], "voxel-paths active blocks A");
  gpu::label_object(GL_BUFFER, blocks_[1], "voxel-paths active blocks B");
}

RelaxationSolver::~RelaxationSolver() {
  GLuint buffers[] = {distances_, changed_, blocks_[0], blocks_[1]};
  glDeleteBuffers(4, buffers);
}

void RelaxationSolver::reset(const VoxelGrid& grid, std::span<const VoxelSource> sources) {
  voxel_count_ = grid.voxel_count();
  std::vector<glm::vec4> n(voxel_count_, glm::vec4(kUnreached, kUnreached, kUnreached, 0.0f));
  for (const VoxelSource& source : sources) n[source.voxel] = glm::min(n[source.voxel], glm::vec4(source.n0, 0.0f));
  glNamedBufferData(distances_, static_cast<GLsizeiptr>(n.size() * sizeof(glm::vec4)), n.data(), GL_DYNAMIC_DRAW);
}

void RelaxationSolver::resize(const VoxelGrid& grid) {
  if (grid.voxel_count() == voxel_count_) return;
  voxel_count_ = grid.voxel_count();
  glNamedBufferData(distances_, static_cast<GLsizeiptr>(voxel_count_ * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_DRAW);
}

RelaxationStats RelaxationSolver::solve(const VoxelGrid& grid, GLuint labels_buffer, GLuint coefficients_buffer,
                                        int check_every, int max_iterations) {
  gpu::DebugGroup group("relax");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingLabels, labels_buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingSigmaT, coefficients_buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingDistances, distances_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingChanged, changed_);
  const GLuint p = program_.id();
  glUseProgram(p);
  glUniform1i(glGetUniformLocation(p, "u_resolution"), grid.resolution);
  glUniform1f(glGetUniformLocation(p, "u_voxel_size"), grid.voxel_size);
  const GLuint groups = (static_cast<GLuint>(grid.resolution) + 3) / 4;
  const bool blocks = schedule_ == RelaxationSchedule::kActiveBlocks;
  const GLuint zero = 0, one = 1;
  int current = 0;  // blocks_[current]: the blocks that changed in the previous sweep
  if (blocks) {
    const std::size_t count = static_cast<std::size_t>(groups) * groups * groups;
    if (count != block_count_) {
      block_count_ = count;
      for (GLuint b : blocks_) glNamedBufferData(b, static_cast<GLsizeiptr>(count * 4), nullptr, GL_DYNAMIC_DRAW);
    }
    glClearNamedBufferData(blocks_[0], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &one);  // first sweep: all
  }
  RelaxationStats stats;
  while (stats.iterations < max_iterations) {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glClearNamedBufferData(changed_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    for (int i = 0; i < check_every && stats.iterations < max_iterations; ++i, ++stats.iterations) {
      if (blocks) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the previous sweep wrote the buffer being cleared
        glClearNamedBufferData(blocks_[1 - current], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingBlocksIn, blocks_[current]);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingBlocksOut, blocks_[1 - current]);
        current = 1 - current;
      }
      glDispatchCompute(groups, groups, groups);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint changed = 1;
    glGetNamedBufferSubData(changed_, 0, 4, &changed);
    if (changed == 0) {
      stats.converged = true;
      break;
    }
  }
  return stats;
}

std::vector<glm::vec3> RelaxationSolver::read_distances() const {
  std::vector<glm::vec4> n(voxel_count_);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(distances_, 0, static_cast<GLsizeiptr>(n.size() * sizeof(glm::vec4)), n.data());
  std::vector<glm::vec3> out(n.size());
  for (std::size_t i = 0; i < n.size(); ++i) out[i] = glm::vec3(n[i]);
  return out;
}

}  // namespace lucent::methods::voxel_paths
